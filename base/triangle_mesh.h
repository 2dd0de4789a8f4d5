#pragma once
// A triangle mesh as an OBJ file holds it: vertex positions, 0-based vertex indices per triangle
// and, when every face names them, normals with their own indices. Nothing merged, reordered or
// repaired, so a reader reports the file as it is. The one mesh type of thaw's mesh files, read
// and written by obj_reader.h / obj_writer.h and checked by edge_topology.h; the renderer and
// the mesher convert from and to their own in-memory types. Knows nothing about VTK, CGAL or
// the renderer.
#include <array>
#include <cstdint>
#include <vector>

namespace thaw::meshio {

struct TriangleMesh {
  /// #V vertex positions [m] (thaw's OBJ files are in metres).
  std::vector<std::array<double, 3>> vertices;
  /// #F by 3 vertex indices, 0-based, in file order (counter-clockwise seen from outside for a
  /// correctly oriented surface). Polygons with more than 3 corners are split into a fan.
  std::vector<std::array<std::int64_t, 3>> triangles;
  /// #N normals as written (not normalised); empty if no face names normals.
  std::vector<std::array<double, 3>> normals;
  /// Empty, or #F by 3 0-based indices into `normals` (when every face corner names one).
  std::vector<std::array<std::int64_t, 3>> normal_triangles;
};

}  // namespace thaw::meshio
