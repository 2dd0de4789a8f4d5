#pragma once
// Wavefront OBJ output of the mesher's TriangleMesh through the one OBJ writer
// (base/obj_writer.h), the contract the renderer and inspector read:
// `v x y z` at 17 significant digits (round-trips doubles exactly), optional `vn` (9 significant
// digits: float precision is plenty for shading normals), 1-based `f i j k` or `f i//i j//j k//k`,
// counter-clockwise seen from outside. Deterministic text (C locale formatting), written
// atomically (temporary file + rename). Knows nothing about CGAL or how the mesh was made.
#include <filesystem>
#include <string>

#include "base/triangle_mesh.h"
#include "src/mesh/triangle_mesh.h"

namespace thaw::mesh {

/// The OBJ text; `comment` (one line, may be empty) is written as a leading `# ` line.
std::string format_obj(const TriangleMesh& mesh, const std::string& comment = "");

/// Writes format_obj(mesh, comment) to `path` atomically; throws thaw::UserError on failure.
void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh,
               const std::string& comment = "");

/// What write_obj builds on the way to the file (the file's mesh and its text, ~1 MB for the
/// default film's surfaces), kept by a caller that writes many meshes on one thread. Allocated
/// afresh for every surface, that memory went back to the kernel after each one whenever the C
/// library's trim threshold happened to be low (it adapts to the process's history: under MPI a
/// rank's history differs), and its ~300 pages were faulted in again for the next: 15% more CPU
/// per surface in a rank than in a single process (docs/pipeline.md).
struct ObjBuffers {
  meshio::TriangleMesh file;
  std::string text;
};

/// write_obj through `buffers` (same bytes).
void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh,
               const std::string& comment, ObjBuffers& buffers);

}  // namespace thaw::mesh
