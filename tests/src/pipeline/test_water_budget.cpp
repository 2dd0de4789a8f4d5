// Tests of src/pipeline/water_budget: the water's mass balance frame by frame, on the solver's
// own output (the default scenario's shell through break-through, and a freezing drop).
#include "src/pipeline/water_budget.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/format/scenario_file.h"
#include "sim/simulate.h"

namespace thaw::pipeline {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;
const sim::ShellGeometry kSphere{};

double ball(double r) {
  return 4.0 / 3.0 * kPi * r * r * r;
}

TEST(WaterBudget, ShapeVolumesAreTheMeshersExactVolumes) {
  // docs/mesh.md's table, evaluated by hand at r = 1 cm, L = 6 cm, S = 10 cm.
  sim::ShellGeometry capsule{sim::Geometry::cylinder, 0.06, 0, true};
  sim::ShellGeometry slab{sim::Geometry::planar, 0, 0.1, false};
  EXPECT_NEAR(shell_surface_volume_m3(kSphere, 0.01), 4.18879020478639e-6, 1e-19);
  EXPECT_NEAR(shell_surface_volume_m3(capsule, 0.01), 1.884955592153876e-5 + 4.18879020478639e-6,
              1e-19);
  EXPECT_NEAR(shell_surface_volume_m3(slab, 0.01),
              2e-4 + 6.283185307179586e-5 + 4.18879020478639e-6, 1e-18);
}

TEST(WaterBudget, HandMadeHistoryAblationThenBreakThrough) {
  // Shell 1 cm -> 2 cm; the front moves out to 1.2 cm, the surface ablates to 1.5 cm, then the
  // two meet at 1.3 cm (break-through).
  std::vector<sim::InterfaceRecord> rows(3);
  rows[0].inner_radius_m = 0.01, rows[0].outer_radius_m = 0.02;
  rows[1].inner_radius_m = 0.012, rows[1].outer_radius_m = 0.015;
  rows[2].inner_radius_m = 0.013, rows[2].outer_radius_m = 0.013;
  const double ri = 917, rw = 1000;
  const auto b = water_budget(rows, kSphere, ri, rw);
  ASSERT_EQ(b.size(), 3u);
  const double m0 = ri * (ball(0.02) - ball(0.01)) + rw * ball(0.01);
  // row 1: drained = the ice ablated outside, 4/3 pi (2^3 - 1.5^3) cm^3, as melt of rho_ice
  EXPECT_NEAR(b[1].drained_melt_mass_kg, ri * (ball(0.02) - ball(0.015)), 1e-15);
  EXPECT_NEAR(b[1].core_water_mass_kg, rw * ball(0.01) + ri * (ball(0.012) - ball(0.01)), 1e-15);
  EXPECT_NEAR(b[1].puddle_volume_m3, b[1].drained_melt_mass_kg / rw, 1e-18);
  EXPECT_EQ(b[1].spilled_mass_kg, 0.0);
  // row 2: no ice: everything is on the floor
  EXPECT_EQ(b[2].ice_mass_kg, 0.0);
  EXPECT_EQ(b[2].core_water_mass_kg, 0.0);
  EXPECT_NEAR(b[2].puddle_volume_m3 * rw, m0, 1e-15);
  for (const auto& x : b) EXPECT_NEAR(x.total_mass_kg(), m0, 1e-15);
}

// The default scenario melts inside and ablates outside until it breaks through after ~38 min:
// at every frame the initial mass is in the ice, the core or the puddle. The budget is exact
// arithmetic on the solver's radii, so the tolerance is rounding: ~10 operations of 1e-16
// relative on masses of ~0.1 kg (1e-14 kg allows 100x that).
TEST(WaterBudget, DefaultRunConservesTheWaterFrameByFrame) {
  const sim::Scenario sc = sim::default_scenario();
  const sim::SimulationResult result = sim::simulate(sc);
  const auto rows = result.interface_records();
  ASSERT_TRUE(result.ended_early);
  const double ri = sc.materials.ice_density_kg_m3, rw = sc.materials.water_density_kg_m3;
  const auto budget = water_budget(rows, kSphere, ri, rw);
  const double m0 =
      ri * (ball(sc.outer_radius_m) - ball(sc.inner_radius_m)) + rw * ball(sc.inner_radius_m);
  double last_puddle = 0;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto& b = budget[k];
    // the solver's own volume columns are the sphere's volumes
    EXPECT_NEAR(b.ice_mass_kg, ri * rows[k].ice_volume_m3, 1e-14) << k;
    EXPECT_NEAR(b.total_mass_kg(), m0, 1e-14) << "frame " << k;
    EXPECT_GE(b.puddle_volume_m3, last_puddle) << "water left the puddle at frame " << k;
    last_puddle = b.puddle_volume_m3;
  }
  // break-through: no water vanishes, it is all on the floor (~106 mL, not 0)
  EXPECT_NEAR(budget.back().puddle_volume_m3 * rw, m0, 1e-14);
  EXPECT_GT(budget.back().spilled_mass_kg, 0.03);
  EXPECT_EQ(budget[rows.size() - 2].spilled_mass_kg, 0.0);
}

TEST(WaterBudget, FreezingDropHasNoPuddleAndKeepsItsMass) {
  // data/scenarios/water_drop_freezing.toml: no ice at t = 0 (not a break-through), a held
  // surface below 0 C (no ablation): nothing reaches the floor.
  const sim::Scenario drop = sim::read_scenario_file(fs::path(THAW_SOURCE_DIR) /
                                                     "data/scenarios/water_drop_freezing.toml");
  const auto rows = sim::simulate(drop).interface_records();
  const auto budget = water_budget(rows, kSphere, 917, 1000);
  for (const auto& b : budget) {
    EXPECT_EQ(b.puddle_volume_m3, 0.0);
    EXPECT_NEAR(b.total_mass_kg(), 1000 * ball(0.01), 1e-15);
  }
}

}  // namespace
}  // namespace thaw::pipeline
