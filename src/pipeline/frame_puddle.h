#pragma once
// The puddle of one film frame: how much water is on the floor (water_budget.h) shaped by
// puddle.h round the ice as the frame places it, added to the frame's scene as a water | outside
// dielectric body. The only place that knows how the shell's shapes sit on the floor.
#include <array>
#include <optional>

#include "render/scene/scene_description.h"
#include "sim/format/interface_history.h"
#include "src/pipeline/puddle.h"

namespace thaw::pipeline {

/// Where the ice stands, for the puddle: the shell's exact outer surface at distance
/// `outer_radius_m` from its core (docs/mesh.md: sphere about the origin, capsule about a segment
/// along z, slab about a square in the x = 0 plane), translated by `offset` [m]. The floor is at
/// floor_y and the ice rests on it. nullopt radius: no ice left.
IceFootprint ice_footprint(const sim::ShellGeometry& geometry, double outer_radius_m,
                           const std::array<double, 3>& offset, double floor_y);

/// Half-length along z of the puddle outline's segment for this geometry (sphere 0, capsule
/// L/2, slab S/2).
double footprint_half_length_m(const sim::ShellGeometry& geometry);

/// Below this volume [m^3] (0.1 microlitre, a drop of 0.6 mm) no puddle is drawn.
constexpr double kSmallestPuddleM3 = 1e-10;

/// Adds the puddle holding `volume_m3` on the floor under `offset` (x, z), around the ice if
/// `ice` is set; nothing below kSmallestPuddleM3. Returns the shape added.
std::optional<PuddleShape> add_puddle(render::SceneDescription& scene, double volume_m3,
                                      double floor_y, const std::array<double, 3>& offset,
                                      const sim::ShellGeometry& geometry,
                                      const std::optional<IceFootprint>& ice,
                                      const std::string& water_medium,
                                      const std::string& outside_medium);

}  // namespace thaw::pipeline
