#include "src/pipeline/frame_puddle.h"

#include <algorithm>
#include <memory>

namespace thaw::pipeline {

double footprint_half_length_m(const sim::ShellGeometry& g) {
  switch (g.geometry) {
    case sim::Geometry::sphere:
      return 0.0;
    case sim::Geometry::cylinder:
      return 0.5 * g.length_m;
    case sim::Geometry::planar:
      return 0.5 * g.lateral_size_m;
  }
  return 0.0;
}

IceFootprint ice_footprint(const sim::ShellGeometry& g, double outer_radius_m,
                           const std::array<double, 3>& offset, double floor_y) {
  IceFootprint f;
  f.radius_m = outer_radius_m;
  f.half_length_m = footprint_half_length_m(g);
  // The slab's core is the square |y|, |z| <= S/2 at x = 0: its lowest part is the edge y = -S/2.
  const double core_bottom = g.geometry == sim::Geometry::planar ? -0.5 * g.lateral_size_m : 0.0;
  // The frame rests the mesh's lowest vertex on the floor; the exact surface dips below it by
  // the mesher's deviation at most, so its lowest point is at or just below the floor.
  f.core_bottom_y = std::min(offset[1] + core_bottom, floor_y + outer_radius_m);
  return f;
}

std::optional<PuddleShape> add_puddle(render::SceneDescription& scene, double volume_m3,
                                      double floor_y, const std::array<double, 3>& offset,
                                      const sim::ShellGeometry& geometry,
                                      const std::optional<IceFootprint>& ice,
                                      const std::string& water_medium,
                                      const std::string& outside_medium) {
  if (!(volume_m3 >= kSmallestPuddleM3)) return std::nullopt;
  const PuddleSettings settings;
  const PuddleShape shape = make_puddle_shape(volume_m3, floor_y, offset[0], offset[2],
                                              footprint_half_length_m(geometry), ice, settings);
  auto mesh = std::make_shared<render::TriangleMesh>(puddle_mesh(shape, settings));
  scene.add_dielectric_mesh(std::move(mesh), water_medium, outside_medium, "puddle");
  return shape;
}

}  // namespace thaw::pipeline
