#pragma once
// An indexed triangle mesh in memory (positions, optional normals) and the checks the renderer
// needs on it: closedness and orientation (a dielectric interface must be a closed,
// outward-oriented surface), smooth normals, a similarity transform. Filled from an OBJ file
// (render/geometry/obj_loader.h) or directly by code (the pipeline's in-memory shell meshes).
// Knows nothing about materials, the BVH or files.
// Why not the file type (base/triangle_mesh.h): the renderer works in single precision with
// 32-bit indices (half the memory of a two-million-triangle mesh, the BVH's own precision) and
// unit normals; from_file_mesh below is the one conversion from the file type.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/triangle_mesh.h"
#include "render/math/vec3.h"

namespace thaw::render {

struct TriangleMesh {
  /// vertex positions [scene units]
  std::vector<Vec3> positions;
  /// #T by 3 indices into `positions`, counter-clockwise seen from outside
  std::vector<std::array<std::uint32_t, 3>> triangles;
  /// shading normals (unit); empty if the mesh has none (flat shading)
  std::vector<Vec3> normals;
  /// #T by 3 indices into `normals`; empty, or the same size as `triangles`
  std::vector<std::array<std::uint32_t, 3>> normal_indices;

  bool has_normals() const { return !normal_indices.empty(); }
};

/// The renderer's mesh from a mesh file's (base/obj_reader.h): positions and normals rounded to
/// float, normals made unit, 32-bit indices. Throws thaw::UserError naming `source` beyond 2^32 - 1
/// vertices or normals, on a zero-length normal, or a coordinate finite in double but not in
/// float (validate_mesh).
TriangleMesh from_file_mesh(const meshio::TriangleMesh& file, const std::string& source);

/// First structural problem of the mesh (index out of range, non-finite coordinate or normal,
/// no triangles), or nullopt if it is usable.
std::optional<std::string> validate_mesh(const TriangleMesh& mesh);

/// Why the mesh is not a closed, consistently oriented 2-manifold (every edge shared by exactly
/// two triangles traversing it in opposite directions; vertices at identical positions are
/// treated as one), or nullopt if it is. Degenerate meshes are reported too.
std::optional<std::string> closed_surface_problem(const TriangleMesh& mesh);

/// Signed enclosed volume [scene units^3] (divergence theorem); > 0 for outward orientation.
double signed_volume(const TriangleMesh& mesh);

/// Replaces the normals by area-weighted vertex normals (vertices at identical positions are
/// smoothed together, so split seams do not show).
void compute_smooth_normals(TriangleMesh& mesh);

/// Turns positions and normals about x, then y, then z by the angles `degrees` (right-handed,
/// about the origin; in double, rounded to float once).
void rotate_mesh(TriangleMesh& mesh, const std::array<double, 3>& degrees);

/// p -> scale * p + translate; normals are unchanged for scale > 0.
void transform_mesh(TriangleMesh& mesh, double scale, const std::array<double, 3>& translate);

}  // namespace thaw::render
