// Tests of the exact surfaces (src/mesh/shell_shape.h): the closed-form volumes and areas against
// independent numerical integration, and the signed distance / normal / support functions.
#include "src/mesh/shell_shape.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace thaw::mesh {
namespace {

ShellShape make(sim::Geometry g, double r, double half) {
  ShellShape s;
  s.geometry = g;
  s.radius_m = r;
  s.core_half_size_m = half;
  return s;
}

// Cross-section area at height x (|x| <= r) of each shape, integrated with composite Simpson:
// an independent route to the Steiner-formula volumes. Simpson is exact to ~(dx)^4 except near
// |x| = r where sqrt(r^2 - x^2) is not smooth; 2e5 intervals leave < 1e-6 relative error there.
double integrate_volume(const ShellShape& s) {
  const double r = s.radius_m, a = 2 * s.core_half_size_m, pi = std::numbers::pi;
  auto section = [&](double x) {
    const double w = std::sqrt(std::max(0.0, r * r - x * x));
    switch (s.geometry) {
      case sim::Geometry::sphere:
        return pi * w * w;
      case sim::Geometry::cylinder:
        return pi * w * w;  // slices across the axis: handled below
      case sim::Geometry::planar:
        return a * a + 4 * a * w + pi * w * w;
    }
    return 0.0;
  };
  const int n = 200000;
  const double h = 2 * r / n;
  double sum = section(-r) + section(r);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * section(-r + i * h);
  double v = sum * h / 3;
  if (s.geometry == sim::Geometry::cylinder) v += pi * r * r * a;  // the straight tube
  return v;
}

TEST(ShellShape, VolumesMatchIntegration) {
  for (auto s : {make(sim::Geometry::sphere, 0.03, 0), make(sim::Geometry::cylinder, 0.02, 0.03),
                 make(sim::Geometry::planar, 0.005, 0.02)})
    EXPECT_NEAR(s.volume() / integrate_volume(s), 1.0, 1e-6) << sim::to_string(s.geometry);
}

TEST(ShellShape, AreaIsTheDerivativeOfVolume) {
  // For a parallel body, dV/dr = A (Steiner); central difference error ~ r^3 (dr)^2 terms only.
  for (auto s : {make(sim::Geometry::sphere, 0.03, 0), make(sim::Geometry::cylinder, 0.02, 0.03),
                 make(sim::Geometry::planar, 0.005, 0.02)}) {
    const double dr = 1e-7;
    ShellShape lo = s, hi = s;
    lo.radius_m -= dr;
    hi.radius_m += dr;
    EXPECT_NEAR((hi.volume() - lo.volume()) / (2 * dr) / s.area(), 1.0, 1e-6)
        << sim::to_string(s.geometry);
  }
}

TEST(ShellShape, SignedDistanceNormalAndSupport) {
  const auto capsule = make(sim::Geometry::cylinder, 0.02, 0.03);
  EXPECT_DOUBLE_EQ(capsule.signed_distance({0.05, 0, 0.01}), 0.03);  // beside the tube
  EXPECT_DOUBLE_EQ(capsule.signed_distance({0, 0, 0.06}), 0.01);     // beyond the cap
  EXPECT_DOUBLE_EQ(capsule.signed_distance({0, 0, 0}), -0.02);
  const Vec3 n = capsule.outward_normal({0, 0.03, 0.06});
  EXPECT_NEAR(n[1], std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(n[2], std::sqrt(0.5), 1e-15);
  const auto slab = make(sim::Geometry::planar, 0.005, 0.02);
  EXPECT_DOUBLE_EQ(slab.signed_distance({0.01, 0.01, -0.01}), 0.005);  // above the flat face
  EXPECT_DOUBLE_EQ(slab.core_support({0, std::sqrt(0.5), -std::sqrt(0.5)}), 0.02 * std::sqrt(2.0));
  // Support of the surface = core support + radius: the farthest surface point along +x.
  EXPECT_DOUBLE_EQ(slab.core_support({1, 0, 0}) + slab.radius_m, 0.005);
  EXPECT_DOUBLE_EQ(make(sim::Geometry::sphere, 0.03, 0).bounding_radius(), 0.03);
}

TEST(ShellShape, FromGeometry) {
  sim::ShellGeometry g;
  g.geometry = sim::Geometry::cylinder;
  g.length_m = 0.08;
  EXPECT_DOUBLE_EQ(ShellShape::from_geometry(g, 0.01).core_half_size_m, 0.04);
  g.geometry = sim::Geometry::planar;
  g.lateral_size_m = 0.05;
  EXPECT_DOUBLE_EQ(ShellShape::from_geometry(g, 0.01).core_half_size_m, 0.025);
}

}  // namespace
}  // namespace thaw::mesh
