#pragma once
// The puddle of melt water on the floor (src/pipeline/water_budget.h says how much): its shape
// and a closed, outward-oriented triangle mesh of it for the renderer (a water | air body).
// Knows nothing of the simulation or of scene files.
//
// Model. A puddle wider than the capillary length l_c = sqrt(gamma / (rho g)) is flat on top
// with height h = 2 l_c sin(theta / 2), theta the contact angle (gravity puddle; de Gennes,
// Brochard-Wyart & Quere, "Capillarity and Wetting Phenomena", Springer 2004, sec. 2.2.1). Water
// at 0 C: gamma = 75.6 mN/m, rho = 999.8 kg/m^3, so l_c = 2.78 mm; theta = 60 degrees (water on
// a lacquered table) gives h = l_c = 2.78 mm. The rim is a circular arc tangent to the top that
// meets the floor at theta (radius h / (1 - cos theta)), a rounded edge. Seen from above, the
// puddle is a stadium (the points within a distance of a segment of half-length L along z;
// L = 0: a disc) centred under the shell: the melt runs down the ice and spreads evenly.
// While ice stands in the puddle, the puddle is a ring whose inner wall follows the ice surface
// at a small air gap (`ice_gap_m`, the surface at distance r + gap from the shell's core; under
// a resting sphere that leaves an air pocket of radius ~sqrt(2 r gap), 3 mm for r = 3 cm): the
// renderer needs every point of space in one medium, and ice | water contact would need the
// ice surface split at the water line. The ring's volume is
// the water's only. A puddle too small for height h is thinner (same contact angle, smaller h).
// The mesh reaches `sink_m` below the floor, so that the floor (opaque) hides its bottom and no
// surface coincides with the floor; only the part above the floor counts as water.
#include <optional>
#include <vector>

#include "render/geometry/triangle_mesh.h"

namespace thaw::pipeline {

struct PuddleSettings {
  /// height of a large puddle [m]: 2 l_c sin(theta/2), l_c = 2.78 mm, theta = 60 deg
  double thickness_m = 2.78e-3;
  /// angle between floor and water surface at the puddle's edge [degrees], in (0, 180)
  double contact_angle_deg = 60.0;
  /// air kept between the ring's inner wall and the exact ice surface, along its normal [m];
  /// well above the mesher's deviation (1e-3 x radius, docs/mesh.md) and ray offsets
  double ice_gap_m = 2e-4;
  /// the mesh extends this far below the floor [m]
  double sink_m = 5e-4;
  /// polygon segments per half circle of the outline (2 x this round a disc)
  int outline_segments = 48;
  /// segments of the inner wall's profile and of the rounded rim's arc
  int wall_segments = 16, rim_segments = 12;
};

/// The ice standing in the puddle: the surface at distance `radius_m` from a core whose lowest
/// part is a horizontal segment of half-length `half_length_m` along z at height `core_bottom_y`
/// (sphere: a point; capsule on its side and upright slab: their lowest edge). The ice rests on
/// the floor: core_bottom_y <= floor_y + radius_m (+ half the gap, for rounding).
struct IceFootprint {
  double radius_m = 0;
  double half_length_m = 0;
  double core_bottom_y = 0;
};

/// Profile of the puddle in (d, y): d = horizontal distance from the outline's segment, y =
/// height above the floor [m].
struct ProfilePoint {
  double d = 0, y = 0;
  /// a sharp corner of the profile: the facets on either side keep their own normals
  bool crease = false;
};

struct PuddleShape {
  double floor_y = 0, center_x = 0, center_z = 0;
  double half_length_m = 0;         ///< segment half-length along z (0: disc)
  double thickness_m = 0;           ///< h: height of the flat top above the floor
  double outer_offset_m = 0;        ///< R: the flat top ends at d = R
  double rim_radius_m = 0;          ///< the rim's arc, centred at (R, h - rim radius)
  double contact_angle_rad = 0;     ///< the rim meets the floor at d = R + rim radius sin(angle)
  std::optional<IceFootprint> ice;  ///< the hole (none: a full puddle)
  double ice_gap_m = 0;

  /// d of the inner wall at height y above the floor (0 without ice).
  double inner_wall_d(double y) const;
  /// Exact volume of water above the floor [m^3] (Steiner: V = 4 L A + 2 pi M with A and M the
  /// profile's area and first moment in d).
  double volume_m3() const;
  /// The profile polygon the mesh sweeps, counter-clockwise in (d, y), including the part below
  /// the floor. With ice a closed loop; without ice an open line from the bottom's centre
  /// (d = 0, below the floor) to the top's centre (d = 0, y = h), the axis closing it.
  std::vector<ProfilePoint> profile(const PuddleSettings& settings) const;
};

/// The puddle holding `volume_m3` of water on the floor y = floor_y, centred at (x, z), around
/// `ice` if some stands in it. Solves the volume for R at height settings.thickness_m, or for a
/// smaller height if even a ring of zero top width would hold too much. Requires volume > 0.
PuddleShape make_puddle_shape(double volume_m3, double floor_y, double center_x, double center_z,
                              double half_length_m, const std::optional<IceFootprint>& ice,
                              const PuddleSettings& settings);

/// Closed, outward-oriented mesh of the shape's profile swept round the stadium outline (no
/// normals: flat facets; smooth normals are computed by the scene builder on request).
render::TriangleMesh puddle_mesh(const PuddleShape& shape, const PuddleSettings& settings);

/// Volume of the mesh's part above y = floor_y [m^3] (divergence theorem with the field
/// (0, max(y - floor_y, 0), 0); exact when no triangle straddles the plane).
double mesh_volume_above(const render::TriangleMesh& mesh, double floor_y);

}  // namespace thaw::pipeline
