#pragma once
// The scene of one film frame: the scenario's scene plus the shell's two interfaces (ice|outside
// and water|ice, meshes in memory) placed as [render.shell] says, and the puddle holding the water
// that left the shell when the shell rests on a floor. Shared by `thaw run` (meshes read from the
// mesh stage's OBJ files) and `thaw gui` (its preview). Knows nothing about files.
#include <array>
#include <memory>
#include <optional>

#include "render/scene/scene_description.h"
#include "sim/format/interface_history.h"
#include "src/pipeline/run_scenario.h"
#include "src/pipeline/water_budget.h"

namespace thaw::pipeline {

/// The shell's surfaces at one step; a null mesh is a surface that has vanished.
struct FrameShell {
  std::shared_ptr<const render::TriangleMesh> outer, inner;
  /// distance of the outer surface from its core [m] (for the puddle's footprint)
  double outer_radius_m = 0;
};

/// Where the shell's meshes (made about the origin) are placed in the frame: [render.shell]
/// center, lowered or raised so the outer surface's lowest point (`outer_min_y` [m], nullopt
/// without an outer surface) touches floor_y when the shell rests on the floor. The one rule for
/// the render and the hand-off exports (handoff_export.h).
std::array<double, 3> shell_offset(const RunScenario& sc, std::optional<double> outer_min_y);

render::SceneDescription frame_scene(const RunScenario& sc, const sim::ShellGeometry& geometry,
                                     const FrameShell& shell, const WaterBudget& water);

}  // namespace thaw::pipeline
