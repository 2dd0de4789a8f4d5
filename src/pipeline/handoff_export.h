#pragma once
// Where the hand-off places a step's surfaces: the offset the renderer gave them (shell_offset of
// frame_scene.h, the one placement rule) from the outer mesh as read from its OBJ. The .vtp series
// of the inspect stage and the OpenVDB volumes take the same offsets; handoff_blender.h records
// them beside the mesh stage's own OBJs (handoff/surfaces.json), so no mesh is stored twice.
// Knows nothing about VTK or rendering beyond the placement.
#include <array>

#include "base/triangle_mesh.h"
#include "src/pipeline/run_scenario.h"

namespace thaw::pipeline {

/// The offset [m] a step's surfaces were rendered at, from its outer mesh as read from its OBJ
/// (nullptr: vanished) and converted as the renderer loads it, so the exports sit where the film
/// shows the shell.
std::array<double, 3> rendered_offset(const RunScenario& sc, const meshio::TriangleMesh* outer);

}  // namespace thaw::pipeline
