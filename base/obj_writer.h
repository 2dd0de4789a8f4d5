#pragma once
// The one OBJ writer: thaw's contract format, read back exactly by obj_reader.h. Vertices with
// 17 significant digits (a double round-trips), normals with 9 (a float round-trips), 1-based
// `f a b c`, or `f a//n ...` when the mesh has normals. Atomic on disk (base/atomic_file.h).
#include <filesystem>
#include <string>

#include "base/triangle_mesh.h"

namespace thaw::meshio {

/// The OBJ text of `mesh`; `comment` (if not empty) becomes a first `# ` line.
std::string format_obj(const TriangleMesh& mesh, const std::string& comment = "");

/// format_obj into `out`, replacing its text but keeping its storage: a caller writing many
/// meshes reuses one buffer instead of allocating (and the C library perhaps returning to the
/// kernel, to fault in again) a fresh one for each.
void format_obj(const TriangleMesh& mesh, const std::string& comment, std::string& out);

/// Writes format_obj(mesh, comment) to `path` atomically; throws thaw::UserError on failure.
void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh,
               const std::string& comment = "");

}  // namespace thaw::meshio
