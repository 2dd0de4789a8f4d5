#pragma once
// An indexed triangle mesh in memory: what the mesher produces and the OBJ writer, the tests and
// the pipeline consume. Plain data, no CGAL; knows nothing about how it was made.
#include <array>
#include <vector>

namespace thaw::mesh {

struct TriangleMesh {
  /// #V vertex positions [m].
  std::vector<std::array<double, 3>> vertices;
  /// #F by 3 zero-based vertex indices, counter-clockwise seen from outside (outward normals).
  std::vector<std::array<int, 3>> faces;
  /// Empty, or #V unit outward vertex normals (gradient of the implicit function).
  std::vector<std::array<double, 3>> normals;
};

/// Volume enclosed by a closed, outward-oriented mesh [m^3]: sum of signed tetrahedra
/// (origin, a, b, c) / 6 (divergence theorem).
double enclosed_volume(const TriangleMesh& mesh);

/// Fills mesh.normals with unit vertex normals: the mean of the incident faces' normals
/// weighted by the face angle at the vertex (Thuermer and Wuethrich 1998), outward for an
/// outward-oriented mesh.
void set_angle_weighted_normals(TriangleMesh& mesh);

/// Total triangle area [m^2].
double surface_area(const TriangleMesh& mesh);

}  // namespace thaw::mesh
