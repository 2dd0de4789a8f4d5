// libFuzzer target: the thaw-mesh/1 manifest reader (base/format/mesh_manifest.h).
#include "base/error.h"
#include "base/format/mesh_manifest.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    thaw::meshio::parse_mesh_manifest(thaw::fuzz::as_text(data, size), "manifest.json");
  } catch (const thaw::UserError&) {
  }
  return 0;
}
