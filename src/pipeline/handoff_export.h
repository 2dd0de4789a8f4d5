#pragma once
// Hand-off of a run to the tools artists and scientists already use: the shell's surfaces in world
// space, exactly where the film shows them (shell_offset of frame_scene.h, the one placement rule),
// as an OBJ sequence Blender imports (DIR/handoff/obj/shell_outer_NNNNNN.obj and
// shell_inner_NNNNNN.obj, metres, y up, one file per frame and surface; a surface that has
// vanished is an OBJ without faces so the sequence has no gaps). The .vtp series of the inspect
// stage takes the same offsets. Knows nothing about VTK or rendering beyond the placement.
#include <array>
#include <filesystem>
#include <vector>

#include "src/mesh/mesh_series.h"
#include "src/pipeline/run_scenario.h"

namespace thaw::pipeline {

/// The offset [m] each step's surfaces were rendered at (index = position in meshes.steps),
/// computed from the outer mesh as the renderer loads it, so the exports sit where the film
/// shows the shell.
std::vector<std::array<double, 3>> rendered_offsets(const RunScenario& sc,
                                                    const std::filesystem::path& mesh_dir,
                                                    const mesh::MeshManifest& meshes);

/// "shell_outer_000012.obj" / "shell_inner_000012.obj".
std::string world_obj_name(long step, bool inner);

/// Writes the OBJ sequence described above into `out_dir` (created; each file atomic). Returns
/// the number of files written.
long write_world_obj_sequence(const std::filesystem::path& mesh_dir,
                              const mesh::MeshManifest& meshes,
                              const std::vector<std::array<double, 3>>& offsets,
                              const std::filesystem::path& out_dir);

}  // namespace thaw::pipeline
