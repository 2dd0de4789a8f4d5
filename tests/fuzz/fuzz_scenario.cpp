// libFuzzer target: the scenario parser (sim/format/scenario_file.h) on arbitrary text.
#include "base/error.h"
#include "sim/format/scenario_file.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    thaw::sim::parse_scenario_string(thaw::fuzz::as_text(data, size), "fuzz.toml");
  } catch (const thaw::UserError&) {
  }
  return 0;
}
