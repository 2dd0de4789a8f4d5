#pragma once
// A triangle mesh as read from a file: vertex positions and 0-based vertex indices, nothing
// merged, reordered or repaired, so the inspector reports the file as it is. Knows nothing about
// VTK or about where the mesh came from.
#include <array>
#include <cstdint>
#include <vector>

namespace thaw::inspect {

struct TriangleMesh {
  /// #V vertex positions [m] (thaw's OBJ files are in metres).
  std::vector<std::array<double, 3>> vertices;
  /// #F by 3 vertex indices, 0-based, in file order (counter-clockwise seen from outside for a
  /// correctly oriented surface). Polygons with more than 3 corners are split into a fan.
  std::vector<std::array<std::int64_t, 3>> triangles;
};

}  // namespace thaw::inspect
