#include "src/pipeline/frame_scene.h"

#include <algorithm>

#include "src/pipeline/frame_puddle.h"

namespace thaw::pipeline {

std::array<double, 3> shell_offset(const RunScenario& sc, std::optional<double> outer_min_y) {
  std::array<double, 3> offset = sc.shell.center;
  if (sc.shell.rest_on_floor && outer_min_y) offset[1] = sc.shell.floor_y - *outer_min_y;
  return offset;
}

render::SceneDescription frame_scene(const RunScenario& sc, const sim::ShellGeometry& geometry,
                                     const FrameShell& shell, const WaterBudget& water) {
  render::SceneDescription desc = sc.scene;
  std::optional<double> min_y;
  if (shell.outer) {
    min_y = shell.outer->positions.front().y;
    for (const auto& p : shell.outer->positions) min_y = std::min<double>(*min_y, p.y);
  }
  const std::array<double, 3> offset = shell_offset(sc, min_y);
  // One surface per interface: ice|outside (outer) and water|ice (inner). Without ice there is
  // no mesh (src/mesh meshes neither surface): a drop before it freezes is not drawn; after a
  // break-through the water is in the puddle.
  if (shell.outer) {
    auto& o = desc.add_dielectric_mesh(shell.outer, sc.shell.ice_medium, sc.shell.outside_medium,
                                       "shell outer surface");
    o.translate = offset;
    if (shell.inner) {
      auto& i = desc.add_dielectric_mesh(shell.inner, sc.shell.water_medium, sc.shell.ice_medium,
                                         "shell inner surface");
      i.translate = offset;
    }
  }
  if (sc.shell.rest_on_floor) {
    std::optional<IceFootprint> ice;
    if (shell.outer) ice = ice_footprint(geometry, shell.outer_radius_m, offset, sc.shell.floor_y);
    add_puddle(desc, water.puddle_volume_m3, sc.shell.floor_y, offset, geometry, ice,
               sc.shell.water_medium, sc.shell.outside_medium);
  }
  return desc;
}

}  // namespace thaw::pipeline
