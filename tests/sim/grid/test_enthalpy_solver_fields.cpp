// The grid solver's output fields (EnthalpySolver::field, sim/grid/grid_field.h) with and without
// natural convection: a run with flow carries the water's velocity at the cell centres, the same
// flow whose largest speed the snapshot reports, still in the ice and the air; a run without flow
// carries none.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "sim/flow/fluid_model.h"
#include "sim/format/scenario_file.h"
#include "sim/grid/enthalpy_solver.h"
#include "sim/grid/grid_builder.h"

namespace thaw::sim {
namespace {

/// A 12 mm ice shell at 0 C holding 10 C water (tests/sim/grid/test_grid_flow.cpp's turn-over
/// shell), axisymmetric or 3D, insulated outside; the flow set on the problem (the file says
/// "none": the scenario rules would refuse the 3D run's 0.9 mm cells for the flow's boundary
/// layer).
GridProblem shell(const char* geometry, double cell_m, bool flow) {
  const std::string text =
      std::string("[simulation]\ngeometry = \"") + geometry +
      "\"\nduration_s = 10.0\noutput_interval_s = 10.0\nflow = \"none\"\ncell_size_m = " +
      std::to_string(cell_m) +
      "\n[shape]\nouter = { kind = \"sphere\", radius_m = 0.012 }\n"
      "cavity = { kind = \"sphere\", radius_m = 0.009 }\n[water]\n"
      "initial_temperature_c = 10.0\n[ice]\ninitial_temperature_c = 0.0\n"
      "[outer_boundary]\nkind = \"insulated\"\n";
  GridProblem problem = build_grid_problem(parse_scenario_string(text, "shell.toml"));
  problem.flow = flow;
  return problem;
}

TEST(EnthalpySolverFields, FlowFieldsCarryTheVelocityOfTheSnapshotsFlow) {
  for (const char* geometry : {"axisymmetric", "3d"}) {
    SCOPED_TRACE(geometry);
    const bool axi = std::string(geometry) == "axisymmetric";
    EnthalpySolver solver(shell(geometry, axi ? 5e-4 : 9e-4, true));
    EXPECT_TRUE(solver.field().has_velocity());  // at rest at t = 0, but kept
    solver.advance_to(axi ? 2.0 : 1.0);
    const GridField f = solver.field();
    ASSERT_EQ(f.velocity_m_s.size(), 3 * f.cell_count());
    double fastest = 0, in_solid = 0;
    for (int k = 0; k < f.cells[2]; ++k)
      for (int j = 0; j < f.cells[1]; ++j)
        for (int i = 0; i < f.cells[0]; ++i) {
          const std::size_t c = f.index(i, j, k);
          double s2 = 0;
          for (int d = 0; d < 3; ++d) s2 += std::pow(double(f.velocity_m_s[3 * c + d]), 2);
          fastest = std::max(fastest, std::sqrt(s2));
          // ice and air (no water in the cell and its neighbours) are held still by the drag
          if (f.water_fraction[c] == 0 && i > 0 && i + 1 < f.cells[0] && j > 0 &&
              j + 1 < f.cells[1] && f.water_fraction[f.index(i - 1, j, k)] == 0 &&
              f.water_fraction[f.index(i + 1, j, k)] == 0 &&
              f.water_fraction[f.index(i, j - 1, k)] == 0 &&
              f.water_fraction[f.index(i, j + 1, k)] == 0) {
            in_solid = std::max(in_solid, std::sqrt(s2));
          }
          if (axi) {
            EXPECT_EQ(f.velocity_m_s[3 * c + 2], 0.0f);  // no swirl
          }
        }
    // The water moves (buoyant flow of a few 10 C in a 9 mm cavity: ~1e-4..1e-2 m/s) ...
    const double reported = solver.snapshot().max_speed_m_s;
    EXPECT_GT(reported, 1e-5);
    // ... the field holds the same cell-centre velocities as the snapshot's largest speed (float
    // rounding of each component: 2^-24 relative) ...
    EXPECT_NEAR(fastest, reported, 1e-6 * reported);
    // ... and a cell of solid surrounded by solid is held still by the Carman-Kozeny drag,
    // D = 1.6e3 / 1e-3 = 1.6e6 /s at no liquid, against at most the buoyancy's spread,
    // g (rho_max - rho(10 C)) / rho_0 = 2.7e-3 m/s^2: below b / D = 1.7e-9 m/s (twice it, for
    // the pressure's share).
    const double b = 9.81 * (flow::kWaterDensityMaxKgM3 - flow::water_density_kg_m3(10.0)) /
                     flow::kWaterDensityMaxKgM3;
    EXPECT_LT(in_solid, 2 * b / 1.6e6);
  }
}

TEST(EnthalpySolverFields, FieldsWithoutFlowCarryNoVelocity) {
  EnthalpySolver solver(shell("axisymmetric", 5e-4, false));
  solver.advance_to(1.0);
  EXPECT_FALSE(solver.field().has_velocity());
  EXPECT_EQ(solver.snapshot().max_speed_m_s, 0.0);
}

}  // namespace
}  // namespace thaw::sim
