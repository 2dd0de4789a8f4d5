#pragma once
// Reads a Wavefront OBJ file into the renderer's TriangleMesh through thaw's one strict OBJ
// reader (base/obj_reader.h: polygons triangulated, 1-based and negative indices, every
// malformed number, index or line an error naming the file and line), then converts: float
// positions, 32-bit indices, unit `vn` normals when every face has them. Errors are
// thaw::UserError naming the file.
#include <filesystem>

#include "render/geometry/triangle_mesh.h"

namespace thaw::render {

/// Loads `path`; throws UserError(path, "line N" or "", problem) if it is missing, unreadable,
/// malformed (non-finite numbers, bad indices) or has no triangles.
TriangleMesh load_obj(const std::filesystem::path& path);

/// Same from OBJ text; `source_name` stands for the file name in errors.
TriangleMesh parse_obj(const std::string& text, const std::string& source_name);

}  // namespace thaw::render
