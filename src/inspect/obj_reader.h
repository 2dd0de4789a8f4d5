#pragma once
// A strict reader for Wavefront OBJ surfaces. vtkOBJReader silently accepts junk (bad indices,
// NaN, unknown statements), so every file is validated here before VTK sees it: each problem is
// a thaw::UserError naming the file and line. Reads `v` and `f` (polygons become triangle fans);
// texture coordinates, normals, groups, materials and smoothing groups are accepted and ignored.
// Knows nothing about VTK.
#include <filesystem>
#include <string>

#include "src/inspect/triangle_mesh.h"

namespace thaw::inspect {

/// Reads an OBJ file; throws thaw::UserError(file, "line N", problem) for a missing file, a
/// malformed or non-finite coordinate, a face index out of range or zero, a face with fewer than
/// 3 corners, an unknown statement, or a file without any face.
TriangleMesh read_obj(const std::filesystem::path& path);

/// Same as read_obj on text; `source_name` stands for the file name in messages.
TriangleMesh parse_obj(const std::string& text, const std::string& source_name);

/// Writes `mesh` as OBJ (17 significant digits, 1-based `f i j k`) atomically. Used by tests and
/// by anyone who wants a mesh on disk in thaw's contract format.
void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh);

}  // namespace thaw::inspect
