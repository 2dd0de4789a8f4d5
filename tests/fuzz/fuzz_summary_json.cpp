// libFuzzer target: the summary.json reader (sim/io/interface_history.h read_shell_geometry).
#include "sim/io/interface_history.h"
#include "src/common/error.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    thaw::sim::read_shell_geometry(thaw::fuzz::as_file(data, size, "summary.json"));
  } catch (const thaw::UserError&) {
  }
  return 0;
}
