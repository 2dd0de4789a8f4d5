// Tests of src/pipeline/puddle: the puddle holds exactly the water asked for, its mesh is closed
// and outward, its volume is the model's to within the derived discretisation error, and it
// never enters the ice standing in it.
#include "src/pipeline/puddle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace thaw::pipeline {
namespace {

constexpr double kPi = std::numbers::pi;

struct Case {
  const char* name;
  double volume_m3;
  double half_length_m;
  std::optional<IceFootprint> ice;
  double floor_y;
};

// The default shell mid-run (3 cm ice resting on the floor, its exact surface dipping 20 um
// below the lowest mesh vertex), a capsule on its side (L/2 = 3 cm), a drop of melt, the whole
// default's water after break-through (106 mL, no ice), and a puddle too small for full height.
std::vector<Case> cases() {
  return {
      {"sphere", 20e-6, 0.0, IceFootprint{0.027, 0.0, 0.027 - 2e-5}, 0.0},
      {"capsule", 30e-6, 0.03, IceFootprint{0.012, 0.03, 0.012}, 0.0},
      {"slab_floor_raised", 50e-6, 0.05, IceFootprint{0.02, 0.05, 0.1 + 0.02}, 0.1},
      {"disc_after_break_through", 106e-6, 0.0, std::nullopt, 0.0},
      {"tiny_ring", 0.05e-6, 0.0, IceFootprint{0.027, 0.0, 0.027}, 0.0},
      {"tiny_drop", 2e-9, 0.0, std::nullopt, 0.0},
  };
}

/// Area and first moment in d of the profile polygon clamped to y >= 0 (shoelace, Green).
void clamped_profile_moments(const std::vector<ProfilePoint>& p, double& area, double& moment) {
  area = moment = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const ProfilePoint a{p[i].d, std::max(p[i].y, 0.0)},
        b{p[(i + 1) % p.size()].d, std::max(p[(i + 1) % p.size()].y, 0.0)};
    const double cr = a.d * b.y - b.d * a.y;
    area += 0.5 * cr;
    moment += cr * (a.d + b.d) / 6.0;
  }
}

double surface_area(const render::TriangleMesh& m) {
  double s = 0;
  for (const auto& t : m.triangles)
    s += 0.5 * length(cross(m.positions[t[1]] - m.positions[t[0]],
                            m.positions[t[2]] - m.positions[t[0]]));
  return s;
}

/// Float rounding of the vertices: each coordinate moves by at most 2^-24 of the largest one,
/// which changes the enclosed volume by at most that distance times the surface area (first
/// order), x sqrt(3) for three coordinates.
double float_rounding_tolerance(const render::TriangleMesh& m) {
  double big = 0;
  for (const auto& p : m.positions)
    big = std::max({big, double(std::abs(p.x)), double(std::abs(p.y)), double(std::abs(p.z))});
  return std::sqrt(3.0) * std::ldexp(big, -24) * surface_area(m);
}

TEST(Puddle, HoldsTheWaterAskedFor) {
  const PuddleSettings st;
  for (const Case& c : cases()) {
    const PuddleShape s =
        make_puddle_shape(c.volume_m3, c.floor_y, 0.01, -0.02, c.half_length_m, c.ice, st);
    EXPECT_NEAR(s.volume_m3(), c.volume_m3, 1e-12 * c.volume_m3) << c.name;
    EXPECT_LE(s.thickness_m, st.thickness_m) << c.name;
    EXPECT_GE(s.outer_offset_m, s.inner_wall_d(s.thickness_m) - 1e-15) << c.name;
  }
}

TEST(Puddle, LargePuddleHasTheCapillaryHeightSmallOnesAreThinner) {
  const PuddleSettings st;
  const PuddleShape big = make_puddle_shape(106e-6, 0, 0, 0, 0, std::nullopt, st);
  EXPECT_EQ(big.thickness_m, st.thickness_m);
  // A flat disc of 2.78 mm holding 106 mL has a radius of about sqrt(V / (pi h)) = 11 cm.
  EXPECT_NEAR(big.outer_offset_m, std::sqrt(106e-6 / (kPi * st.thickness_m)), 0.01);
  const PuddleShape drop = make_puddle_shape(2e-9, 0, 0, 0, 0, std::nullopt, st);
  EXPECT_LT(drop.thickness_m, st.thickness_m);
}

TEST(Puddle, MeshIsClosedOutwardAndSweepsItsProfileExactly) {
  // The mesh is the profile polygon swept round the outline polygon: every facet between two
  // rings is planar (the rings are parallel offsets), so its volume above the floor is exactly
  // V = 4 L A_p + 2 M sin(pi / M) M_p (Steiner for the 2M-gon of area M sin(pi/M) per unit
  // offset squared), up to float rounding of the vertices.
  const PuddleSettings st;
  const double mm = st.outline_segments, poly = mm * std::sin(kPi / mm);
  for (const Case& c : cases()) {
    const PuddleShape s =
        make_puddle_shape(c.volume_m3, c.floor_y, 0.01, -0.02, c.half_length_m, c.ice, st);
    const render::TriangleMesh mesh = puddle_mesh(s, st);
    EXPECT_EQ(render::closed_surface_problem(mesh), std::nullopt) << c.name;
    EXPECT_EQ(render::validate_mesh(mesh), std::nullopt) << c.name;
    EXPECT_GT(render::signed_volume(mesh), 0) << c.name;
    for (const auto& t : mesh.triangles) {
      const float lo =
          std::min({mesh.positions[t[0]].y, mesh.positions[t[1]].y, mesh.positions[t[2]].y});
      const float hi =
          std::max({mesh.positions[t[0]].y, mesh.positions[t[1]].y, mesh.positions[t[2]].y});
      ASSERT_FALSE(lo < float(c.floor_y) && hi > float(c.floor_y))
          << c.name << ": a facet straddles the floor";
    }
    double a = 0, m = 0;
    clamped_profile_moments(s.profile(st), a, m);
    const double expected = 4 * s.half_length_m * a + 2 * poly * m;
    EXPECT_NEAR(mesh_volume_above(mesh, c.floor_y), expected, float_rounding_tolerance(mesh))
        << c.name;
  }
}

TEST(Puddle, MeshIsClosedForEveryVolumeOfARun) {
  // Early in a run the puddle is a ring of zero top width whose outer edge lies within ~1e-12 m
  // of the ice wall: profile points distinct in double that round to the same float. Every
  // volume from the smallest drawn to a whole default run's water must still give a closed
  // mesh, with the shell resting on the floor (as the pipeline places it) and offset from the
  // origin (as in a scene).
  const PuddleSettings st;
  for (double v = 1e-10; v < 2e-4; v *= 1.37) {
    for (const double dip : {0.0, 2e-5}) {
      const IceFootprint ice{0.03, 0.0, 0.03 - dip};
      const PuddleShape s = make_puddle_shape(v, 0.0, 0.0, 0.0, 0.0, ice, st);
      const render::TriangleMesh mesh = puddle_mesh(s, st);
      ASSERT_EQ(render::closed_surface_problem(mesh), std::nullopt) << "volume " << v;
      EXPECT_GT(render::signed_volume(mesh), 0) << "volume " << v;
    }
  }
}

TEST(Puddle, MeshVolumeIsTheModelVolumeToDiscretisationError) {
  // V_mesh - V = 4 L (A_p - A) + 2 s (M_p - M) - 2 (pi - s) M with s = M sin(pi/M) the
  // outline polygon's factor. |A_p - A| <= dA, the area between the arcs and their chords
  // (rho^2 / 2 (t - sin t) per chord of angle t on an arc of radius rho: the rim and the inner
  // wall), |M_p - M| <= d_max dA, and 2 pi M <= V. Hence
  // |V_mesh - V| <= (1 - s / pi) V + (4 L + 2 pi d_max) dA  (+ float rounding).
  const PuddleSettings st;
  const double mm = st.outline_segments, s_poly = mm * std::sin(kPi / mm);
  const auto chords = [](double rho, double angle, int n) {
    const double t = angle / n;
    return n * 0.5 * rho * rho * (t - std::sin(t));
  };
  for (const Case& c : cases()) {
    const PuddleShape s =
        make_puddle_shape(c.volume_m3, c.floor_y, 0.01, -0.02, c.half_length_m, c.ice, st);
    const render::TriangleMesh mesh = puddle_mesh(s, st);
    double da = chords(s.rim_radius_m, s.contact_angle_rad, st.rim_segments);
    if (s.ice) {  // the wall: arc of radius r + gap from its angle at the floor to the water line's
      const double r = s.ice->radius_m + s.ice_gap_m, c = s.ice->core_bottom_y - s.floor_y;
      const double span = std::acos(std::clamp((c - s.thickness_m) / r, 0.0, 1.0)) -
                          std::acos(std::clamp(c / r, 0.0, 1.0));
      da += chords(r, span, st.wall_segments);
    }
    const double d_max = s.outer_offset_m + s.rim_radius_m;
    const double bound =
        (1 - s_poly / kPi) * c.volume_m3 + (4 * s.half_length_m + 2 * kPi * d_max) * da;
    const double v_mesh = mesh_volume_above(mesh, c.floor_y);
    EXPECT_NEAR(v_mesh, c.volume_m3, bound + float_rounding_tolerance(mesh)) << c.name;
    // and the bound is of the right size: 48 segments per half circle leave (pi/48)^2/6 = 0.07 %
    // of the volume, the profile's chords less, except in puddles thinner than their rim
    if (c.volume_m3 >= 1e-6) {
      EXPECT_LT(bound, 2e-3 * c.volume_m3) << c.name;
    }
  }
}

TEST(Puddle, NeverEntersTheIce) {
  // Every vertex and facet centroid above the floor lies outside the exact ice surface (the
  // points within radius r of the core's lowest segment) by at least half the air gap: the wall
  // is at r + gap, its chords sag inwards by at most (r + gap)(1 - cos(t / 2)) (t < 90/16
  // degrees: 3 um at r = 3 cm) and the outline's by d (1 - cos(pi / 96)) (15 um), both < gap/2.
  const PuddleSettings st;
  for (const Case& c : cases()) {
    if (!c.ice) continue;
    const PuddleShape s =
        make_puddle_shape(c.volume_m3, c.floor_y, 0.01, -0.02, c.half_length_m, c.ice, st);
    const render::TriangleMesh mesh = puddle_mesh(s, st);
    const auto distance_to_core = [&](const render::Vec3& p) {
      const double dz = std::max(0.0, std::abs(p.z - s.center_z) - c.ice->half_length_m);
      const double dy = std::max(0.0, c.ice->core_bottom_y - p.y);
      return std::sqrt((p.x - s.center_x) * (p.x - s.center_x) + dy * dy + dz * dz);
    };
    for (const auto& t : mesh.triangles) {
      const render::Vec3 centroid =
          (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0f;
      for (const render::Vec3& p : {mesh.positions[t[0]], centroid})
        if (p.y >= c.floor_y) {
          ASSERT_GT(distance_to_core(p), c.ice->radius_m + 0.5 * st.ice_gap_m) << c.name;
        }
    }
  }
}

}  // namespace
}  // namespace thaw::pipeline
