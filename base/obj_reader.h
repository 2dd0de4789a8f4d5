#pragma once
// The one strict reader of Wavefront OBJ surfaces (render, mesh and inspect all read through
// it). Every problem is a thaw::UserError naming the file and line: a malformed, non-finite or
// missing coordinate, trailing junk on a line, a face index that is zero, not an integer
// ("1.5"), out of range or beyond 64 bits ("4294967298" in a 3-vertex file), a face with fewer
// than 3 corners, an unknown statement, a last line cut off without its line end (a truncated
// file), or a file without faces. Reads `v`, `vn` and `f` (polygons become triangle fans);
// texture coordinates are checked and dropped, groups, materials and smoothing groups ignored.
#include <filesystem>
#include <string>

#include "base/triangle_mesh.h"

namespace thaw::meshio {

/// Reads an OBJ file; throws thaw::UserError(file, "line N" or "", problem) as described above,
/// also for a missing file or a path that is a directory.
TriangleMesh read_obj(const std::filesystem::path& path);

/// Same as read_obj on text; `source_name` stands for the file name in messages.
TriangleMesh parse_obj(const std::string& text, const std::string& source_name);

}  // namespace thaw::meshio
