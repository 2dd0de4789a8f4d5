#include "src/gui/preview_scene.h"

#include <algorithm>
#include <cmath>

#include "src/pipeline/frame_camera.h"
#include "src/pipeline/frame_scene.h"
#include "src/pipeline/water_budget.h"

namespace thaw::gui {

std::vector<PreviewPass> preview_passes(int width, int height, int samples) {
  // Quick passes: 1 sample, no caustics, 6 Whitted levels (enough to see through the ice shell
  // and the water: camera, outer, inner surface, water, inner, outer, floor), one shadow ray per
  // sphere light. On the default scene a 320x240 one costs 0.075 s of CPU (scene build
  // included) against 0.054 s + 0.075 s for the former half-size pass followed by it
  // (bench/gui/bench_preview_passes): the preview size comes first, so the 320x240 image an
  // edit waits for is the first one rendered. Only previews larger than kQuickPixels start
  // with a quick pass of that many pixels at the same aspect ratio.
  constexpr int kQuickDepth = 6;
  constexpr long kQuickPixels = 320L * 240L;
  std::vector<PreviewPass> passes;
  const long pixels = static_cast<long>(width) * height;
  if (pixels > kQuickPixels) {
    const double shrink = std::sqrt(static_cast<double>(kQuickPixels) / pixels);
    passes.push_back({std::max(1, static_cast<int>(width * shrink)),
                      std::max(1, static_cast<int>(height * shrink)), 1, false, false, kQuickDepth,
                      true});
  }
  passes.push_back({width, height, 1, false, false, kQuickDepth, true});
  passes.push_back({width, height, std::max(2, samples), true, true, 0, false});
  return passes;
}

render::SceneDescription preview_scene(const pipeline::RunScenario& sc, const ShellStep& step,
                                       const std::vector<sim::InterfaceRecord>& camera_rows,
                                       const PreviewPass& pass) {
  const sim::ShellGeometry geometry = shell_geometry(sc.simulation);
  pipeline::FrameShell shell{step.outer, step.inner, step.row.outer_radius_m};
  // The water that left the shell by this step, measured from the run's first row.
  const sim::InterfaceRecord first = camera_rows.empty() ? step.row : camera_rows.front();
  const auto water =
      pipeline::water_budget({first, step.row}, geometry, sc.simulation.materials.ice_density_kg_m3,
                             sc.simulation.materials.water_density_kg_m3);
  render::SceneDescription desc = pipeline::frame_scene(sc, geometry, shell, water.back());
  const double aspect = static_cast<double>(pass.width) / pass.height;
  if (!sc.camera_set)
    desc.camera = pipeline::framing_camera(
        pipeline::shell_extent(camera_rows.empty() ? std::vector{step.row} : camera_rows, geometry,
                               sc.shell.center, sc.shell.rest_on_floor, sc.shell.floor_y),
        aspect);
  desc.image.width = pass.width;
  desc.image.height = pass.height;
  desc.image.adaptive = pass.adaptive;
  desc.image.samples_per_pixel =
      pass.adaptive ? std::max(pass.samples, desc.image.min_samples) : pass.samples;
  if (!pass.caustics) desc.caustics.enabled = false;
  if (pass.max_depth > 0) desc.image.max_depth = std::min(desc.image.max_depth, pass.max_depth);
  if (pass.one_shadow_ray)
    for (auto& light : desc.lights) light.samples = 1;
  return desc;
}

}  // namespace thaw::gui
