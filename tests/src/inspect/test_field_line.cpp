// Tests of src/inspect/field_line (`thaw inspect --over-line`): on fields that are linear in the
// coordinates, linear interpolation between cell centres is exact, so every sample must equal the
// analytic field to the float rounding of the stored values; beyond the outermost centres the
// outermost value is held; the axisymmetric field is revolved (u_r into (u_x, u_z)); bad lines,
// points outside the grid and missing steps are UserErrors naming the option.
#include "src/inspect/field_line.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "base/error.h"
#include "sim/format/grid_field_file.h"
#include "tests/src/inspect/test_meshes.h"

namespace thaw::inspect {
namespace {
namespace fs = std::filesystem;

// The analytic 3D field, in the field's coordinates [m].
double t3(const Point3& p) {
  return 2.0 + 100.0 * p[0] - 300.0 * p[1] + 50.0 * p[2];
}
double w3(const Point3& p) {
  return 0.5 + 10.0 * p[0];
}
Point3 u3(const Point3& p) {
  return {1e-3 + 0.1 * p[1], -0.2 * p[0], 0.05 * p[2]};
}

sim::GridField cube(bool with_velocity) {
  sim::GridField f;
  f.geometry = sim::GridField::Geometry::cartesian3d;
  f.cells = {6, 5, 4};
  f.origin_m = {-0.015, -0.01, 0.002};
  f.spacing_m = 0.005;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 6; ++i) {
        const Point3 c{f.origin_m[0] + (i + 0.5) * f.spacing_m,
                       f.origin_m[1] + (j + 0.5) * f.spacing_m,
                       f.origin_m[2] + (k + 0.5) * f.spacing_m};
        f.temperature_c.push_back(static_cast<float>(t3(c)));
        f.water_fraction.push_back(static_cast<float>(w3(c)));
        f.ice_fraction.push_back(0.0f);
        if (with_velocity)
          for (double v : u3(c)) f.velocity_m_s.push_back(static_cast<float>(v));
      }
  return f;
}

// float rounding of a stored value of magnitude `scale` (2^-24 relative), a few times over.
double tolerance(double scale) {
  return 4 * std::ldexp(std::abs(scale), -24);
}

TEST(FieldLine, LinearFieldIsSampledExactlyInsideTheCentres) {
  const sim::GridField f = cube(true);
  // corner centre to corner centre, through the body of the grid
  const Point3 a{-0.0125, -0.0075, 0.0045}, b{0.0125, 0.0125, 0.0195};
  const std::vector<LineSample> s = sample_over_line(f, a, b, 11);
  ASSERT_EQ(s.size(), 11u);
  EXPECT_EQ(s.front().position_m, a);
  EXPECT_EQ(s.back().position_m, b);
  for (const LineSample& x : s) {
    const Point3& p = x.position_m;
    EXPECT_NEAR(x.temperature_c, t3(p), tolerance(5)) << p[0];
    EXPECT_NEAR(x.liquid_fraction, w3(p), tolerance(1));
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(x.velocity_m_s[d], u3(p)[d], tolerance(3e-3)) << d;
  }
  // evenly spaced: the midpoint sample is the segment's midpoint
  for (int d = 0; d < 3; ++d) EXPECT_DOUBLE_EQ(s[5].position_m[d], 0.5 * (a[d] + b[d]));
}

TEST(FieldLine, OutermostValueIsHeldBetweenTheLastCentreAndTheBorder) {
  const sim::GridField f = cube(false);
  // on the grid's x_min border and half-way to the first centre: the first centre's x
  const LineSample border = sample_field(f, {-0.015, 0.0, 0.01});
  const LineSample centre = sample_field(f, {-0.0125, 0.0, 0.01});
  EXPECT_EQ(border.temperature_c, centre.temperature_c);
  EXPECT_NEAR(centre.temperature_c, t3({-0.0125, 0.0, 0.01}), tolerance(5));
  // no velocity in the field: zeros
  EXPECT_EQ(border.velocity_m_s, (Point3{0, 0, 0}));
}

TEST(FieldLine, AxisymmetricFieldIsRevolvedWithItsRadialVelocity) {
  sim::GridField f;
  f.geometry = sim::GridField::Geometry::axisymmetric;
  f.cells = {8, 6, 1};
  f.origin_m = {0, -0.012, 0};
  f.spacing_m = 0.004;
  // T = 3 + 200 r - 100 y, u_r = 0.01 r, u_y = 1e-3 + 0.02 r
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 8; ++i) {
      const double r = (i + 0.5) * f.spacing_m, y = f.origin_m[1] + (j + 0.5) * f.spacing_m;
      f.temperature_c.push_back(static_cast<float>(3 + 200 * r - 100 * y));
      f.water_fraction.push_back(static_cast<float>(20 * r));
      f.ice_fraction.push_back(0.0f);
      f.velocity_m_s.insert(f.velocity_m_s.end(), {static_cast<float>(0.01 * r),
                                                   static_cast<float>(1e-3 + 0.02 * r), 0.0f});
    }
  // across the axis along x at y = 1 mm: u_x = u_r x / r = 0.01 x on both sides, and inside the
  // first half cell too (u_r falls linearly to 0 at the axis)
  for (const LineSample& s : sample_over_line(f, {-0.03, 0.001, 0}, {0.03, 0.001, 0}, 61)) {
    const double x = s.position_m[0], r = std::max(std::abs(x), 0.5 * f.spacing_m);
    EXPECT_NEAR(s.temperature_c, 3 + 200 * r - 100 * 0.001, tolerance(10)) << x;
    EXPECT_NEAR(s.velocity_m_s[0], 0.01 * x, tolerance(3e-4)) << x;
    EXPECT_NEAR(s.velocity_m_s[1], 1e-3 + 0.02 * r, tolerance(2e-3)) << x;
    EXPECT_EQ(s.velocity_m_s[2], 0.0);
  }
  // along z the radial velocity is u_z
  const LineSample z = sample_field(f, {0, 0, 0.01});
  EXPECT_EQ(z.velocity_m_s[0], 0.0);
  EXPECT_NEAR(z.velocity_m_s[2], 0.01 * 0.01, tolerance(1e-4));
  // off the plane: r = hypot(x, z)
  const LineSample d = sample_field(f, {0.006, 0.0, 0.008});
  EXPECT_NEAR(d.temperature_c, 3 + 200 * 0.01, tolerance(10));
  EXPECT_NEAR(d.velocity_m_s[0], 0.01 * 0.006, tolerance(1e-4));
  EXPECT_NEAR(d.velocity_m_s[2], 0.01 * 0.008, tolerance(1e-4));
  // beyond the grid's radius (8 cells of 4 mm)
  EXPECT_THROW(sample_field(f, {0.0321, 0, 0}), UserError);
}

TEST(FieldLine, LineEndsAreParsedOrRefusedNamingTheOption) {
  const auto ends = parse_line_ends("0,-0.01,2e-3; 1.5 ,0.25,-3");
  EXPECT_EQ(ends[0], (Point3{0, -0.01, 2e-3}));
  EXPECT_EQ(ends[1], (Point3{1.5, 0.25, -3}));
  for (const char* bad :
       {"", "0,0,0", "0,0,0;1,1", "0,0,0;1,1,1;2,2,2", "0,0,0;1,1,1,", "a,0,0;1,1,1",
        "0,0,0;1,1,inf", "0,0,nan;1,1,1", "0,0,0;1,,1", "1e999,0,0;0,0,0"}) {
    try {
      parse_line_ends(bad);
      FAIL() << "accepted \"" << bad << "\"";
    } catch (const UserError& e) {
      EXPECT_EQ(e.where(), "--over-line") << bad;
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  }
}

TEST(FieldLine, PointsOutsideTheGridAreRefused) {
  const sim::GridField f = cube(true);
  try {
    sample_over_line(f, {0, 0, 0.01}, {0.02, 0, 0.01}, 3);  // x ends at 0.015
    FAIL() << "sampled outside the grid";
  } catch (const UserError& e) {
    EXPECT_EQ(e.where(), "--over-line");
    EXPECT_NE(e.problem().find("outside the fields' grid (x from -0.015 to 0.015 m)"),
              std::string::npos)
        << e.problem();
  }
}

TEST(FieldLine, StepFilesAreFoundOrRefused) {
  testing::ScratchDir dir("field_line_steps");
  EXPECT_THROW(field_file_of_step(dir.path(), std::nullopt), UserError);
  fs::create_directories(dir.path() / "fields");
  for (int s : {0, 1, 2}) {
    char name[32];
    std::snprintf(name, sizeof name, "step_%06d.grid", s);
    sim::write_grid_field(dir.path() / "fields" / name, cube(false));
  }
  EXPECT_EQ(field_file_of_step(dir.path(), std::nullopt).filename(), "step_000002.grid");
  EXPECT_EQ(field_file_of_step(dir.path(), 1).filename(), "step_000001.grid");
  for (long bad : {3L, -1L}) {
    try {
      field_file_of_step(dir.path(), bad);
      FAIL() << bad;
    } catch (const UserError& e) {
      EXPECT_EQ(e.where(), "--step");
      EXPECT_NE(e.problem().find("step_000000 to step_000002"), std::string::npos) << e.problem();
    }
  }
}

TEST(FieldLine, CsvHasTheHeaderAndShortestNumbers) {
  LineSample s;
  s.position_m = {0.1, -0.2, 0};
  s.temperature_c = 4.0;
  s.liquid_fraction = 1;
  s.velocity_m_s = {1e-3, -2.5e-4, 0};
  EXPECT_EQ(format_line_csv({s}),
            "x_m,y_m,z_m,temperature_c,liquid_fraction,ux_m_s,uy_m_s,uz_m_s\n"
            "0.1,-0.2,0,4,1,0.001,-0.00025,0\n");
}

}  // namespace
}  // namespace thaw::inspect
