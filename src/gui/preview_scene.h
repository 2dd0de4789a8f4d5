#pragma once
// The scene the preview renders: the film frame `thaw run` would render for a shell step
// (src/pipeline/frame_scene.h: the scenario's scene, the shell placed as [render.shell], the
// puddle), framed by the run's built-in camera unless the scenario sets one, at the preview's
// size and sample count. One pass of the progressive preview is this scene at that pass's
// quality. Qt-free.
#include <vector>

#include "render/scene/scene_description.h"
#include "src/gui/shell_step.h"
#include "src/pipeline/run_scenario.h"

namespace thaw::gui {

/// One pass of the progressive preview.
struct PreviewPass {
  int width = 320, height = 240;
  /// samples per pixel (the cap when adaptive)
  int samples = 1;
  bool adaptive = false;
  /// photon-mapped caustics as the scene sets them (off for the quick passes)
  bool caustics = false;
  /// quick passes: at most this many Whitted levels and one shadow ray per sphere light and
  /// shading point (0: the scene's own depth and samples)
  int max_depth = 0;
  bool one_shadow_ray = false;
};

/// The passes for a preview of `width` x `height` with up to `samples` per pixel: the preview
/// size at quick settings (1 sample, no caustics, fewer levels and shadow rays), then at the
/// scene's own settings (adaptive up to `samples`, caustics). A preview larger than 320x240
/// starts with a quick pass of 320x240's pixel count, shown scaled to the preview size.
std::vector<PreviewPass> preview_passes(int width, int height, int samples);

/// The frame scene of `step`; `camera_rows` are the rows the built-in camera frames (all of a
/// simulated run, so scrubbing keeps one camera; or the initial row alone).
render::SceneDescription preview_scene(const pipeline::RunScenario& scenario, const ShellStep& step,
                                       const std::vector<sim::InterfaceRecord>& camera_rows,
                                       const PreviewPass& pass);

}  // namespace thaw::gui
