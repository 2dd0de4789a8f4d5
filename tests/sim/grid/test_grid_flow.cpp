// Natural convection in the grid solver's water (sim/grid/grid_flow.h): the turn-over of water's
// density maximum. An ice shell at its melting point, insulated outside, holding water: at 10 C
// the water cooled at the ice (towards 4 C, denser) sinks along the walls and the warm water
// gathers under the roof, which melts first; at 2 C the water cooled at the ice (towards 0 C,
// lighter) rises, and the floor melts first. Conduction alone melts both halves alike. The
// energy balance holds to the solver's usual 1e-8 per step with the advected heat.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "sim/format/scenario_file.h"
#include "sim/grid/enthalpy_solver.h"
#include "sim/grid/grid_builder.h"

namespace thaw::sim {
namespace {

struct HalfMelt {
  double top = 0, bottom = 0;  // liquid volume gained above and below the centre [m^3]
  double max_energy_error = 0;
};

HalfMelt melt_halves(double water_c, bool flow, double seconds) {
  const std::string text =
      "[simulation]\ngeometry = \"axisymmetric\"\nduration_s = " + std::to_string(seconds) +
      "\noutput_interval_s = " + std::to_string(seconds) +
      "\ncell_size_m = 5e-4\n[shape]\nouter = { kind = \"sphere\", radius_m = 0.012 }\n"
      "cavity = { kind = \"sphere\", radius_m = 0.009 }\n[water]\ninitial_temperature_c = " +
      std::to_string(water_c) +
      "\n[ice]\ninitial_temperature_c = 0.0\n[outer_boundary]\nkind = \"insulated\"\n";
  GridProblem problem = build_grid_problem(parse_scenario_string(text, "turn_over.toml"));
  problem.flow = flow;
  const double centre_y = 0.0;
  EnthalpySolver solver(problem);
  auto liquid_halves = [&](double& top, double& bottom) {
    const std::vector<double> f = solver.liquid_fraction();
    top = bottom = 0;
    for (int j = 0; j < problem.cells[1]; ++j)
      for (int i = 0; i < problem.cells[0]; ++i) {
        const long c = static_cast<long>(i) + static_cast<long>(problem.cells[0]) * j;
        const double y = problem.origin_m[1] + (j + 0.5) * problem.spacing_m;
        (y > centre_y ? top : bottom) += f[c] * solver.cell_volume(i, j, 0);
      }
  };
  double top0, bottom0;
  liquid_halves(top0, bottom0);
  solver.advance_to(seconds);
  HalfMelt r;
  liquid_halves(r.top, r.bottom);
  r.top -= top0;
  r.bottom -= bottom0;
  r.max_energy_error = solver.statistics().max_step_energy_error;
  std::printf(
      "water %.0f C, flow %d: melted above the centre %.3g mm^3, below %.3g mm^3, "
      "energy error %.2e, steps %ld\n",
      water_c, flow, 1e9 * r.top, 1e9 * r.bottom, r.max_energy_error, solver.statistics().steps);
  return r;
}

TEST(GridFlow, WarmWaterMeltsTheRoofFirstColdWaterTheFloor) {
  const double seconds = 60;
  const HalfMelt still = melt_halves(10.0, false, seconds);
  const HalfMelt warm = melt_halves(10.0, true, seconds);
  const HalfMelt cold = melt_halves(2.0, true, seconds);
  // Conduction: the shell is symmetric about its centre, the halves melt alike (the grid's
  // halves are mirror images: rounding only).
  EXPECT_NEAR(still.top, still.bottom, 1e-6 * (still.top + still.bottom));
  // Convection turns the melt over: the asymmetry changes sign with the water's side of 4 C,
  // and is at least a tenth of the melt (measured: 20 % at 10 C, 15 % at 2 C after 60 s; the
  // conduction run's is rounding).
  EXPECT_GT(warm.top - warm.bottom, 0.1 * (warm.top + warm.bottom));
  EXPECT_GT(cold.bottom - cold.top, 0.1 * (cold.top + cold.bottom));
  for (const HalfMelt* r : {&still, &warm, &cold}) EXPECT_LT(r->max_energy_error, 1e-8);
}

}  // namespace
}  // namespace thaw::sim

#include <numbers>

#include "sim/flow/fluid_model.h"
#include "sim/simulate.h"

namespace thaw::sim {
namespace {

TEST(GridFlow, LargestSpeedAndRayleighPerOutput) {
  const Scenario sc = parse_scenario_string(
      "[simulation]\ngeometry = \"axisymmetric\"\nduration_s = 10.0\noutput_interval_s = 5.0\n"
      "cell_size_m = 4.5e-4\nflow = \"natural_convection\"\n[shape]\nouter = { kind = \"sphere\", "
      "radius_m = 0.008 }\ncavity = { kind = \"sphere\", radius_m = 0.006 }\n[water]\n"
      "initial_temperature_c = 10.0\n[ice]\ninitial_temperature_c = 0.0\n[outer_boundary]\n"
      "kind = \"insulated\"\n",
      "records.toml");
  const SimulationResult r = simulate(sc);
  ASSERT_EQ(r.flow_records.size(), 3u);
  // t = 0: at rest; the Rayleigh number from its definition with the initial liquid: the
  // density spread over [0, 10] C is rho(4.0293) - rho(10), D from the liquid volume, nu at the
  // liquid's mean temperature (below 10 C: the cavity's cut cells hold ice at 0 C too), read
  // from the output field (floats: 1e-6).
  EXPECT_EQ(r.flow_records[0][1], 0.0);
  const double volume = r.snapshots[0].liquid_volume_m3;
  const GridField& f0 = r.fields[0];
  double w = 0, wt = 0;
  for (std::size_t c = 0; c < f0.temperature_c.size(); ++c) {
    const int i = static_cast<int>(c % f0.cells[0]);
    const double ring = (i + 0.5) * f0.spacing_m;  // the ring's volume is 2 pi r h^2
    w += f0.water_fraction[c] * ring;
    wt += f0.water_fraction[c] * ring * f0.temperature_c[c];
  }
  const double d = std::cbrt(6 * volume / std::numbers::pi);
  const Materials& m = sc.materials;
  const double expected = 9.81 * (flow::kWaterDensityMaxKgM3 - flow::water_density_kg_m3(10.0)) /
                          flow::kWaterDensityMaxKgM3 * d * d * d /
                          (flow::water_viscosity_pa_s(wt / w) / flow::kWaterDensityMaxKgM3 *
                           (m.water_conductivity_w_mk / m.water_heat_capacity()));
  std::printf("Rayleigh %.4g (expected %.4g), speeds %.3g %.3g mm/s\n", r.flow_records[0][2],
              expected, 1e3 * r.flow_records[1][1], 1e3 * r.flow_records[2][1]);
  EXPECT_NEAR(r.flow_records[0][2], expected, 1e-6 * expected);
  EXPECT_GT(r.flow_records[1][1], 1e-5);  // moving by 5 s
  EXPECT_GT(r.flow_records[2][1], 1e-5);
}

}  // namespace
}  // namespace thaw::sim

namespace thaw::sim {
namespace {

/// Liquid volume gained above and below the centre after `seconds` by a hollow ice sphere at its
/// melting point (16 mm radius, 9 mm cavity of water at 10 C, insulated outside) on the
/// axisymmetric or the 3D grid, with the flow on.
HalfMelt sphere_halves(const std::string& geometry, double cell_m, double seconds) {
  const std::string text =
      "[simulation]\ngeometry = \"" + geometry + "\"\nduration_s = " + std::to_string(seconds) +
      "\noutput_interval_s = " + std::to_string(seconds) +
      "\ncell_size_m = " + std::to_string(cell_m) +
      "\nflow = \"none\"\n[shape]\nouter = { kind = \"sphere\", radius_m = 0.016 }\n"
      "cavity = { kind = \"sphere\", radius_m = 0.009 }\n[water]\ninitial_temperature_c = 10.0\n"
      "[ice]\ninitial_temperature_c = 0.0\n[outer_boundary]\nkind = \"insulated\"\n";
  // The flow set on the problem: the scenario rules would refuse these cells, which span the
  // water's boundary layer (~1.1 mm) less than twice; the test compares two discretisations on
  // equal cells, not either against the truth.
  GridProblem problem = build_grid_problem(parse_scenario_string(text, "revolution.toml"));
  problem.flow = true;
  EnthalpySolver solver(problem);
  auto halves = [&](double& top, double& bottom) {
    const std::vector<double> f = solver.liquid_fraction();
    top = bottom = 0;
    for (int k = 0; k < problem.cells[2]; ++k)
      for (int j = 0; j < problem.cells[1]; ++j)
        for (int i = 0; i < problem.cells[0]; ++i) {
          const long c = i + static_cast<long>(problem.cells[0]) *
                                 (j + static_cast<long>(problem.cells[1]) * k);
          const double y = problem.origin_m[1] + (j + 0.5) * problem.spacing_m;
          (y > 0 ? top : bottom) += f[c] * solver.cell_volume(i, j, k);
        }
  };
  double top0, bottom0;
  halves(top0, bottom0);
  solver.advance_to(seconds);
  HalfMelt r;
  halves(r.top, r.bottom);
  r.top -= top0;
  r.bottom -= bottom0;
  r.max_energy_error = solver.statistics().max_step_energy_error;
  std::printf("%s, %.1f mm cells: melted above the centre %.4g mm^3, below %.4g mm^3 (%ld steps)\n",
              geometry.c_str(), 1e3 * cell_m, 1e9 * r.top, 1e9 * r.bottom,
              solver.statistics().steps);
  return r;
}

TEST(GridFlow, AxisymmetricAgreesWithThe3dRunOfTheSameBody) {
  // The same body of revolution on both grids: the axisymmetric grid resolves the sphere in
  // (r, y), the 3D grid stair-steps it, and both discretise the flow to first order at the
  // interface (the enthalpy-porosity drag and the stair-stepped or ring cells). Each run's own
  // discretisation error is estimated from the same run at twice the cell (first order: the
  // error at h is about |q(h) - q(2h)|); the two must agree within the sum of those estimates.
  const double seconds = 40, h = 0.001;
  const HalfMelt a1 = sphere_halves("axisymmetric", h, seconds);
  const HalfMelt a2 = sphere_halves("axisymmetric", 2 * h, seconds);
  const HalfMelt c1 = sphere_halves("3d", h, seconds);
  const HalfMelt c2 = sphere_halves("3d", 2 * h, seconds);
  for (auto part : {&HalfMelt::top, &HalfMelt::bottom}) {
    const double tolerance = std::abs(a1.*part - a2.*part) + std::abs(c1.*part - c2.*part);
    std::printf("axisymmetric %.4g vs 3D %.4g mm^3: differ by %.3g, allowed %.3g\n",
                1e9 * (a1.*part), 1e9 * (c1.*part), 1e9 * std::abs(a1.*part - c1.*part),
                1e9 * tolerance);
    EXPECT_LE(std::abs(a1.*part - c1.*part), tolerance);
  }
  // Both turn the melt over the same way (10 C water: the roof first).
  EXPECT_GT(a1.top, a1.bottom);
  EXPECT_GT(c1.top, c1.bottom);
  for (const HalfMelt* r : {&a1, &a2, &c1, &c2}) EXPECT_LT(r->max_energy_error, 1e-8);
}

}  // namespace
}  // namespace thaw::sim
