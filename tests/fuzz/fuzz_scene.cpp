// libFuzzer target: the scene parser (render/format/scene_parser.h) on arbitrary text. Mesh files
// resolve against an empty folder, so only absolute paths reach the file system.
#include "base/error.h"
#include "render/format/scene_parser.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    thaw::render::parse_scene_string(thaw::fuzz::as_text(data, size), "fuzz.toml",
                                     "/nonexistent-thaw-fuzz");
  } catch (const thaw::UserError&) {
  }
  return 0;
}
