// material_temperature_c (src/inspect/field_probe.h) against fields whose answer is known in
// closed form. Tolerances: the field stores float temperatures, each within |T| * 2^-24 of the
// exact value; the probe is a convex combination of stored values, so it is within
// max|T| * 2^-24 (< 1e-6 for the |T| < 10 used here) of the exact interpolant, plus double
// round-off. 1e-6 is therefore a bound, not a fit.
#include "src/inspect/field_probe.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace thaw::inspect {
namespace {

constexpr double kTol = 1e-6;

/// A field of `cells` with cell-centred temperature t(centre) and material fraction m(i, j, k).
sim::GridField make_field(sim::GridField::Geometry g, std::array<int, 3> cells,
                          std::array<double, 3> origin, double h,
                          const std::function<double(double, double, double)>& t,
                          const std::function<double(int, int, int)>& material) {
  sim::GridField f;
  f.geometry = g;
  f.cells = cells;
  f.origin_m = origin;
  f.spacing_m = h;
  for (int k = 0; k < cells[2]; ++k)
    for (int j = 0; j < cells[1]; ++j)
      for (int i = 0; i < cells[0]; ++i) {
        const double x = origin[0] + (i + 0.5) * h, y = origin[1] + (j + 0.5) * h,
                     z = origin[2] + (k + 0.5) * h;
        f.temperature_c.push_back(static_cast<float>(t(x, y, z)));
        const double m = material(i, j, k);
        f.ice_fraction.push_back(static_cast<float>(0.5 * m));
        f.water_fraction.push_back(static_cast<float>(0.5 * m));
      }
  return f;
}

double linear(double x, double y, double z) {
  return 2 + 30 * x - 50 * y + 70 * z;
}

TEST(FieldProbe, LinearFieldInsideMaterialIsExact) {
  // Trilinear interpolation reproduces a linear field exactly.
  const auto f = make_field(sim::GridField::Geometry::cartesian3d, {6, 5, 4}, {-0.02, 0.01, 0.03},
                            0.01, linear, [](int, int, int) { return 1.0; });
  for (const std::array<double, 3> p : {std::array<double, 3>{-0.012, 0.018, 0.037},
                                        {0.0, 0.03, 0.05},
                                        {0.031, 0.052, 0.061},
                                        {0.0149, 0.0341, 0.0499}})
    EXPECT_NEAR(material_temperature_c(f, p), linear(p[0], p[1], p[2]), kTol);
}

TEST(FieldProbe, AirCellsDoNotPullTheSurfaceTowardTheAirTemperature) {
  // Cells with x index >= 3 are air held at 500 C. Between the centres of columns 2 and 3 only
  // column 2 holds material, so the value is the field there, bilinear in y and z.
  const auto f = make_field(
      sim::GridField::Geometry::cartesian3d, {6, 5, 4}, {0, 0, 0}, 0.01,
      [](double x, double y, double z) { return x >= 0.03 ? 500.0 : linear(x, y, z); },
      [](int i, int, int) { return i >= 3 ? 0.0 : 1.0; });
  const std::array<double, 3> p{0.029, 0.021, 0.017};
  EXPECT_NEAR(material_temperature_c(f, p), linear(0.025, p[1], p[2]), kTol);
}

TEST(FieldProbe, CellsWeightedByTheirMaterialFraction) {
  // Two cells along x, material 1 and 0.5, temperatures 1 and 4; the midpoint has trilinear
  // weights 1/2, 1/2: (1 * 1 + 0.5 * 4) / (1 + 0.5) = 2.
  const auto f = make_field(
      sim::GridField::Geometry::cartesian3d, {2, 1, 1}, {0, 0, 0}, 1.0,
      [](double x, double, double) { return x < 1 ? 1.0 : 4.0; },
      [](int i, int, int) { return i == 0 ? 1.0 : 0.5; });
  EXPECT_NEAR(material_temperature_c(f, {1.0, 0.5, 0.5}), 2.0, kTol);
  // No material among the eight: the nearest material cell within two cells (here x index 3,
  // at 7 C; the air cells around it are at 100 C).
  const auto remnant = make_field(
      sim::GridField::Geometry::cartesian3d, {5, 1, 1}, {0, 0, 0}, 1.0,
      [](double x, double, double) { return x > 3 && x < 4 ? 7.0 : 100.0; },
      [](int i, int, int) { return i == 3 ? 0.2 : 0.0; });
  EXPECT_NEAR(material_temperature_c(remnant, {1.0, 0.5, 0.5}), 7.0, kTol);
  // No material at all: the plain trilinear value.
  const auto air = make_field(
      sim::GridField::Geometry::cartesian3d, {2, 1, 1}, {0, 0, 0}, 1.0,
      [](double x, double, double) { return x < 1 ? 1.0 : 4.0; },
      [](int, int, int) { return 0.0; });
  EXPECT_NEAR(material_temperature_c(air, {1.0, 0.5, 0.5}), 2.5, kTol);
}

TEST(FieldProbe, AxisymmetricFieldIsRevolvedAboutY) {
  // T = 1 + 40 r + 20 y on the (r, y) half-plane; any azimuth gives the same value, and inside
  // the first cell centre (r < h / 2) the axis value is held (dT/dr = 0 by symmetry there for a
  // smooth field; here the held value is that of the first centres).
  const double h = 0.005;
  const auto t = [](double r, double y, double) { return 1 + 40 * r + 20 * y; };
  const auto f = make_field(sim::GridField::Geometry::axisymmetric, {8, 4, 1}, {0, -0.01, 0}, h, t,
                            [](int, int, int) { return 1.0; });
  for (const double angle : {0.0, 0.7, 2.0, 4.1}) {
    const double r = 0.0213, y = -0.0031;
    const std::array<double, 3> p{r * std::cos(angle), y, r * std::sin(angle)};
    EXPECT_NEAR(material_temperature_c(f, p), t(r, y, 0), kTol) << angle;
  }
  EXPECT_NEAR(material_temperature_c(f, {0.0005, 0.0, -0.0005}), t(h / 2, 0.0, 0), kTol);
}

TEST(FieldProbe, BeyondTheOuterCentresTheEdgeValueIsHeld) {
  const auto f = make_field(sim::GridField::Geometry::cartesian3d, {3, 3, 3}, {0, 0, 0}, 0.01,
                            linear, [](int, int, int) { return 1.0; });
  EXPECT_NEAR(material_temperature_c(f, {-1.0, 0.015, 0.015}), linear(0.005, 0.015, 0.015), kTol);
  EXPECT_NEAR(material_temperature_c(f, {0.015, 0.015, 7.0}), linear(0.015, 0.015, 0.025), kTol);
}

}  // namespace
}  // namespace thaw::inspect
