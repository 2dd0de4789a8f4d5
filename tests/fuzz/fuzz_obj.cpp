// libFuzzer target: the strict OBJ reader (base/obj_reader.h) and, on what it accepts, the
// edge topology and the writer's round trip (read(write(m)) == m for the vertices and triangles).
#include <cstdlib>

#include "base/edge_topology.h"
#include "base/error.h"
#include "base/obj_reader.h"
#include "base/obj_writer.h"
#include "tests/fuzz/fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace thaw::meshio;
  TriangleMesh m;
  try {
    m = parse_obj(thaw::fuzz::as_text(data, size), "fuzz.obj");
  } catch (const thaw::UserError&) {
    return 0;
  }
  std::vector<std::array<std::int64_t, 3>> distinct;
  for (const auto& t : m.triangles)
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) distinct.push_back(t);
  edge_topology(m.vertices, distinct);
  const TriangleMesh back = parse_obj(format_obj(m), "round-trip.obj");
  if (back.vertices != m.vertices || back.triangles != m.triangles) std::abort();
  return 0;
}
