// libFuzzer target: the summary.json reader (sim/format/interface_history.h read_shell_geometry).
#include "base/error.h"
#include "sim/format/interface_history.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    thaw::sim::read_shell_geometry(thaw::fuzz::as_file(data, size, "summary.json"));
  } catch (const thaw::UserError&) {
  }
  return 0;
}
