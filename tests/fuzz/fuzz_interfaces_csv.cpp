// libFuzzer target: the interfaces.csv reader (sim/format/interface_history.h) on arbitrary bytes.
#include "base/error.h"
#include "sim/format/interface_history.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    thaw::sim::read_interfaces_csv(thaw::fuzz::as_file(data, size, "interfaces.csv"));
  } catch (const thaw::UserError&) {
  }
  return 0;
}
