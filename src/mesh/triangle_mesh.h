#pragma once
// An indexed triangle mesh in memory: what the mesher produces and the OBJ writer, the tests and
// the pipeline consume. Plain data, no CGAL; knows nothing about how it was made.
// Why not the file type (base/triangle_mesh.h): the mesher's algorithms (CGAL output, grid
// marching tetrahedra, remeshing, Taubin smoothing) keep one unit normal per vertex and int
// indices; the file type keeps what an OBJ file says (normals with their own indices, 64-bit
// indices). to_file_mesh / from_file_mesh below are the one conversion between the two.
#include <array>
#include <vector>

#include "base/triangle_mesh.h"

namespace thaw::mesh {

struct TriangleMesh {
  /// #V vertex positions [m].
  std::vector<std::array<double, 3>> vertices;
  /// #F by 3 zero-based vertex indices, counter-clockwise seen from outside (outward normals).
  std::vector<std::array<int, 3>> faces;
  /// Empty, or #V unit outward vertex normals (gradient of the implicit function).
  std::vector<std::array<double, 3>> normals;
};

/// The mesh as thaw's mesh files hold it: the same vertices and triangles; vertex normals, if
/// any, indexed like the vertices.
meshio::TriangleMesh to_file_mesh(const TriangleMesh& mesh);

/// to_file_mesh into `file`, replacing its contents but keeping its storage (one buffer reused
/// over many meshes).
void to_file_mesh(const TriangleMesh& mesh, meshio::TriangleMesh& file);

/// The mesher's mesh from a file's: vertices and triangles as they are; the normals only when
/// the file indexes them like the vertices (as to_file_mesh writes them), else none. THAW_CHECK
/// that the vertex count fits int indices (the reader has checked every index against it).
TriangleMesh from_file_mesh(const meshio::TriangleMesh& file);

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
