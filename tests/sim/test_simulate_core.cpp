// sim's core alone (thaw_sim_core: no TOML, no JSON; this binary links nothing else): a scenario
// built in code is validated, simulated and named for its problems without the file layer
// (sim/format/scenario_file.h, sim/format/simulation_output.h). A core that reached for a file
// format would not link.
#include <gtest/gtest.h>

#include <cmath>

#include "base/error.h"
#include "sim/scenario/scenario_rules.h"
#include "sim/simulate.h"

namespace thaw::sim {
namespace {

TEST(SimulateCore, RunsAScenarioBuiltInCode) {
  Scenario sc;  // a hollow ice sphere (2 cm core of 10 C water, 3 cm ice at -5 C) in 20 C air
  sc.duration_s = 600;
  sc.output_interval_s = 300;
  const SimulationResult r = simulate(sc);
  ASSERT_EQ(r.snapshots.size(), 3u);
  // Warm air outside and warm water inside: both fronts move into the ice.
  EXPECT_LT(r.snapshots.back().outer_radius_m, sc.outer_radius_m);
  EXPECT_GT(r.snapshots.back().inner_radius_m, sc.inner_radius_m);
  // The solver closes its energy balance to round-off relative to the scenario's energy scale
  // (1e-10: the bound tests/sim/stefan1d/test_front_fixing.cpp uses after a whole run).
  for (const Snapshot& s : r.snapshots) EXPECT_LT(std::abs(s.energy_balance_error), 1e-10);
}

TEST(SimulateCore, RulesNameTheKeyWithoutTheParser) {
  Scenario sc;
  sc.inner_radius_m = 0.05;  // larger than the outer radius
  const auto problem = find_scenario_problem(sc);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->key, "shell.inner_radius_m");
  EXPECT_THROW(simulate(sc), UserError);
}

}  // namespace
}  // namespace thaw::sim
