// The rules of grid scenarios (sim/grid/grid_rules.h) through the parser: every bad [shape] or
// resolution gives one UserError naming the file, the key and the problem with its numbers.
#include "sim/grid/grid_rules.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "base/error.h"
#include "sim/format/scenario_file.h"

namespace thaw::sim {
namespace {

std::string scenario(const std::string& geometry, const std::string& shape,
                     const std::string& sim_extra = "") {
  return "[simulation]\ngeometry = \"" + geometry +
         "\"\nduration_s = 60.0\noutput_interval_s = 30.0\n" + sim_extra + "\n[shape]\n" + shape +
         "\n[water]\ninitial_temperature_c = 10.0\n[ice]\ninitial_temperature_c = -5.0\n"
         "[outer_boundary]\nkind = \"convective\"\ntemperature_c = "
         "25.0\nheat_transfer_coefficient_w_m2k = 50.0\n";
}

const std::string kCube = "outer = { kind = \"box\", size_m = [0.04, 0.04, 0.04] }\n";

/// Parsing must fail with a one-line message containing the file, `key` and `fragment`.
void expect_refused(const std::string& text, const std::string& key, const std::string& fragment) {
  try {
    parse_scenario_string(text, "bad.toml");
    FAIL() << "accepted: " << text;
  } catch (const UserError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad.toml"), std::string::npos) << what;
    EXPECT_NE(what.find(key), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(GridRules, ValidShapesParse) {
  const Scenario s = parse_scenario_string(
      scenario(
          "3d",
          kCube +
              "cavity = { kind = \"box\", size_m = [0.024, 0.024, 0.024], edge_radius_m = 0.002 }",
          "flow = \"none\""),
      "good.toml");
  EXPECT_EQ(s.grid, GridGeometry::cartesian3d);
  ASSERT_TRUE(s.shape.cavity.has_value());
  EXPECT_EQ(s.shape.cavity->edge_radius_m, 0.002);
  // default cell without flow: 1/48 of the 4 cm extent (the 8 mm wall is 9.6 cells); with flow
  // it also spans the water's boundary layer (TooCoarseForTheFlowsBoundaryLayerSaysWhatIsNeeded)
  EXPECT_NEAR(effective_cell_size_m(s), 0.04 / kDefaultCellsAcross3d, 1e-15);
  const Scenario a = parse_scenario_string(
      scenario("axisymmetric",
               "outer = { kind = \"cylinder\", radius_m = 0.02, height_m = 0.06 }\n"
               "cavity = { kind = \"sphere\", radius_m = 0.01, center_m = [0, 0.01, 0] }"),
      "good.toml");
  EXPECT_EQ(a.grid, GridGeometry::axisymmetric);
}

TEST(GridRules, MaxStepHasAPhysicalFloor) {
  // The floor is a cell's diffusion time over the widest admitted temperature span: for ice
  // (alpha = 2.22 / (917 * 2050) = 1.181e-6 m^2/s, larger than water's 1.34e-7) and 1 mm
  // cells, 1e-6 / 1.181e-6 / 1273.15 = 6.65e-4 s.
  const Materials ice;
  EXPECT_NEAR(smallest_max_step_s(ice, 1e-3), 1e-6 / (2.22 / (917.0 * 2050.0)) / 1273.15, 1e-12);
  const std::string cell = "cell_size_m = 0.001\n";
  for (const char* tiny : {"1e-9", "1e-320", "0.0006"})
    expect_refused(scenario("3d", kCube, cell + "max_step_s = " + tiny), "simulation.max_step_s",
                   "below the smallest useful step");
  expect_refused(scenario("axisymmetric", "outer = { kind = \"sphere\", radius_m = 0.02 }",
                          cell + "max_step_s = 1e-9"),
                 "simulation.max_step_s", "0.000665");
  // just above the floor is a valid (if slow) scenario
  EXPECT_NO_THROW(
      parse_scenario_string(scenario("3d", kCube, cell + "max_step_s = 0.0007"), "good.toml"));
}

TEST(GridRules, CavityMustLieStrictlyInside) {
  expect_refused(scenario("3d", kCube + "cavity = { kind = \"box\", size_m = [0.04, 0.02, 0.02] }"),
                 "shape.cavity", "strictly inside");
  expect_refused(
      scenario("3d",
               kCube + "cavity = { kind = \"sphere\", radius_m = 0.01, center_m = [0.015, 0, 0] }"),
      "shape.cavity", "outside");
  expect_refused(
      scenario("3d",
               kCube + "cavity = { kind = \"sphere\", radius_m = 0.01, center_m = [0.1, 0, 0] }"),
      "shape.cavity", "outside");
}

TEST(GridRules, AxisymmetricAcceptsOnlyBodiesOfRevolutionOnTheAxis) {
  expect_refused(scenario("axisymmetric", kCube), "shape.outer.kind",
                 "only spheres and vertical cylinders");
  expect_refused(
      scenario("axisymmetric",
               "outer = { kind = \"sphere\", radius_m = 0.02, center_m = [0.01, 0, 0] }"),
      "shape.outer.center_m", "y axis");
}

TEST(GridRules, SizesKindsAndKeys) {
  expect_refused(scenario("3d", "outer = { kind = \"sphere\", radius_m = 0.0 }"), "radius_m",
                 "must be positive");
  expect_refused(scenario("3d", "outer = { kind = \"box\", size_m = [0.04, -0.01, 0.04] }"),
                 "size_m", "positive");
  expect_refused(scenario("3d", "outer = { kind = \"cone\", radius_m = 0.02 }"), "kind",
                 "unknown kind 'cone'");
  expect_refused(
      scenario("3d", "outer = { kind = \"sphere\", radius_m = 0.02, size_m = [1, 1, 1] }"),
      "size_m", "unknown key");
  expect_refused(
      scenario(
          "3d",
          kCube + "cavity = { kind = \"box\", size_m = [0.02, 0.02, 0.02], edge_radius_m = 0.5 }"),
      "edge_radius_m", "half the smallest edge");
  expect_refused(scenario("cube", kCube), "geometry", "unknown geometry 'cube'");
  expect_refused(scenario("3d", kCube, "cells_per_phase = 10"), "cells_per_phase", "1D");
}

TEST(GridRules, TooCoarseForTheThinnestWallGivesTheNumbers) {
  // 8 mm walls with 4 mm cells: 2 cells, at least 3 needed, so cell_size_m <= 8/3 mm
  expect_refused(
      scenario("3d", kCube + "cavity = { kind = \"box\", size_m = [0.024, 0.024, 0.024] }",
               "cell_size_m = 0.004"),
      "cell_size_m", "0.008 m = 2 cells, at least 3 are needed (use cell_size_m <= 0.00266");
}

// Issue 27: an OBJ shape with one vertex at 1e308 was blamed on simulation.cell_size_m ("needs inf
// cells"), a key the file did not hold. Now the OBJ file is named, with the span and the unit;
// so is a 1 km sphere.
// Issue 24's bad input: a grid too coarse for the flow's boundary layer names the resolution it
// needs. A linear fluid makes the numbers exact: Ra = g beta dT L^3 / (nu alpha) with
// nu = mu / rho_0, alpha = k / (rho c), and delta = L Ra^(-1/4) must span 2 cells.
TEST(GridRules, TooCoarseForTheFlowsBoundaryLayerSaysWhatIsNeeded) {
  const std::string shell =
      "outer = { kind = \"sphere\", radius_m = 0.01 }\n"
      "cavity = { kind = \"sphere\", radius_m = 0.006 }\n";
  const std::string fluid =
      "[materials]\nwater_density_model = \"linear\"\nwater_expansion_per_k = 2e-4\n"
      "water_viscosity_pa_s = 1e-3\n";
  const double L = 0.012, ra = 9.81 * 2e-4 * 10.0 * L * L * L / (1e-3 / 1000.0 * 0.56 / 4.186e6);
  const double delta = L * std::pow(ra, -0.25);  // 0.53 mm
  // 0.3 mm cells: 1.8 across the layer, refused, naming the cell size that is needed
  for (const char* geometry : {"axisymmetric", "3d"}) {
    const std::string text =
        scenario(geometry, shell, "flow = \"natural_convection\"\ncell_size_m = 0.0003") + fluid;
    const std::string fragment = "needs at least 2 cells across it: use cell_size_m <= ";
    expect_refused(text, "simulation.cell_size_m", fragment);
    try {
      parse_scenario_string(text, "bad.toml");
    } catch (const UserError& e) {
      const std::string what = e.what();
      const double needed = std::stod(what.substr(what.find(fragment) + fragment.size()));
      EXPECT_NEAR(needed, delta / 2, 1e-6 * delta) << what;
      EXPECT_NE(what.find("(or flow = \"none\")"), std::string::npos) << what;
    }
  }
  // 0.25 mm cells: 2.1 across it, and the same grid without flow: accepted
  EXPECT_NO_THROW(parse_scenario_string(
      scenario("axisymmetric", shell, "flow = \"natural_convection\"\ncell_size_m = 0.00025") +
          fluid,
      "ok.toml"));
  EXPECT_NO_THROW(parse_scenario_string(
      scenario("axisymmetric", shell, "flow = \"none\"\ncell_size_m = 0.0003") + fluid, "ok.toml"));
  // The shipped flow scenario's default cells (0.5 mm) span its layer (1.3 mm at Ra 8.5e5)
  EXPECT_NO_THROW(read_scenario_file(std::filesystem::path(THAW_SOURCE_DIR) /
                                     "data/scenarios/hollow_sphere_flow.toml"));
  // Without cell_size_m, the default cell spans the layer with 2 cells when the water flows (the
  // default wherever there is water): the shipped hollow cube's 24 mm cavity of 10 C water needs
  // 0.58 mm, finer than 1/48 of its 4 cm (0.83 mm), which it keeps without flow.
  const Scenario cube = read_scenario_file(std::filesystem::path(THAW_SOURCE_DIR) /
                                           "data/scenarios/hollow_cube.toml");
  EXPECT_TRUE(cube.natural_convection);
  const double layer = cavity_flow_scale(cube, 0.024).boundary_layer_m;
  EXPECT_NEAR(effective_cell_size_m(cube), layer / 2, 1e-12);
  Scenario still = cube;
  still.natural_convection = false;
  EXPECT_NEAR(effective_cell_size_m(still), 0.04 / 48, 1e-12);
  EXPECT_NO_THROW(read_scenario_file(std::filesystem::path(THAW_SOURCE_DIR) /
                                     "data/scenarios/obj_pebble.toml"));
}

TEST(GridRules, FarOutBodyNamesItsFileNotTheCellSize) {
  const std::filesystem::path obj =
      std::filesystem::path(THAW_BINARY_DIR) / "test-tmp" / "grid_rules_far.obj";
  std::filesystem::create_directories(obj.parent_path());
  std::ofstream(obj) << "v -0.02 -0.02 -0.02\nv 0.02 -0.02 -0.02\nv 0 0.02 -0.02\nv 0 0 1e308\n"
                        "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  const std::string text =
      scenario("3d", "outer = { kind = \"obj\", file = \"" + obj.string() + "\" }");
  expect_refused(text, "shape.outer.file", "grid_rules_far.obj) spans [-0.02, 1e+308] m along z");
  try {
    parse_scenario_string(text, "bad.toml");
  } catch (const UserError& e) {
    EXPECT_EQ(std::string(e.what()).find("cell_size_m"), std::string::npos) << e.what();
  }
  expect_refused(scenario("3d", "outer = { kind = \"sphere\", radius_m = 500.0 }"), "shape.outer",
                 "at most 100 m across");
}

}  // namespace
}  // namespace thaw::sim
