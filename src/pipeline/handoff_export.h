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

#include "base/triangle_mesh.h"
#include "src/pipeline/run_scenario.h"

namespace thaw::pipeline {

/// The offset [m] a step's surfaces were rendered at, from its outer mesh as read from its OBJ
/// (nullptr: vanished) and converted as the renderer loads it, so the exports sit where the film
/// shows the shell.
std::array<double, 3> rendered_offset(const RunScenario& sc, const meshio::TriangleMesh* outer);

/// "shell_outer_000012.obj" / "shell_inner_000012.obj".
std::string world_obj_name(long step, bool inner);

/// Writes one file of the OBJ sequence described above into `out_dir` (atomic): step `step`'s
/// surface `placed` (already in world space; nullptr: vanished) at simulated time `time_s`.
void write_world_obj(const std::filesystem::path& out_dir, long step, double time_s, bool inner,
                     const meshio::TriangleMesh* placed);

}  // namespace thaw::pipeline
