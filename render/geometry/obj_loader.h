#pragma once
// Reads a Wavefront OBJ file into a TriangleMesh with tinyobjloader (polygons triangulated,
// 1-based and negative indices, `vn` normals kept when every face has them). A pre-pass checks
// that every `v`/`vn` number is finite and well formed (tinyobjloader silently reads "nan" as 0)
// so a bad file is reported with its line. Errors are thaw::UserError naming the file.
#include <filesystem>

#include "render/geometry/triangle_mesh.h"

namespace thaw::render {

/// Loads `path`; throws UserError(path, "line N" or "", problem) if it is missing, unreadable,
/// malformed (non-finite numbers, bad indices) or has no triangles.
TriangleMesh load_obj(const std::filesystem::path& path);

/// Same from OBJ text; `source_name` stands for the file name in errors.
TriangleMesh parse_obj(const std::string& text, const std::string& source_name);

}  // namespace thaw::render
