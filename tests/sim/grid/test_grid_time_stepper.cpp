// The grid solver's time stepper (sim/grid/grid_time_stepper.h) stops when asked: between
// steps and within a step's Newton and CG iterations, so a grid run ends within a second of
// Ctrl-C or SIGTERM whatever its step size; a stopped solver continues bit for bit as if never
// stopped; and the runaway guard ends a run whose steps could never reach its end.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>

#include "base/error.h"
#include "base/interrupt.h"
#include "sim/format/scenario_file.h"
#include "sim/grid/enthalpy_solver.h"
#include "sim/grid/grid_builder.h"
#include "sim/simulate.h"

namespace thaw::sim {
namespace {

using Clock = std::chrono::steady_clock;

/// A hollow 3D cube in warm air: 2.4 cm, 0.4 mm cells (about 250000 cells with the air
/// border), so one step takes tens of milliseconds of CPU.
Scenario hollow_cube(const std::string& sim_extra = "") {
  return parse_scenario_string(
      "[simulation]\ngeometry = \"3d\"\nduration_s = 600.0\noutput_interval_s = 300.0\n"
      "cell_size_m = 0.0004\nflow = \"none\"\n" +
          sim_extra +
          "\n[shape]\nouter = { kind = \"box\", size_m = [0.024, 0.024, 0.024] }\n"
          "cavity = { kind = \"sphere\", radius_m = 0.008 }\n"
          "[water]\ninitial_temperature_c = 10.0\n[ice]\ninitial_temperature_c = -5.0\n"
          "[outer_boundary]\nkind = \"convective\"\ntemperature_c = 25.0\n"
          "heat_transfer_coefficient_w_m2k = 50.0\n",
      "cube.toml");
}

/// Seconds from `since` to now.
double seconds_since(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

TEST(GridTimeStepper, StopFromAnotherThreadEndsAdvanceWithinASecond) {
  EnthalpySolver solver(build_grid_problem(hollow_cube()));
  std::atomic<bool> stop{false};
  std::atomic<long long> raised_ns{0};
  std::thread raiser([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    raised_ns = Clock::now().time_since_epoch().count();
    stop = true;
  });
  const double reached = solver.advance_to(600, [&] { return stop.load(); });
  const auto returned = Clock::now();
  raiser.join();
  // the run takes minutes: it was stopped, not finished, and promptly
  EXPECT_LT(reached, 600);
  EXPECT_FALSE(solver.finished());
  const double latency_s =
      std::chrono::duration<double>(returned.time_since_epoch() - Clock::duration(raised_ns.load()))
          .count();
  EXPECT_LT(latency_s, 1.0);
  // the state is the last accepted step's: the energy books still balance
  EXPECT_LT(solver.snapshot().energy_balance_error, 1e-8);
}

TEST(GridTimeStepper, AStoppedSolverContinuesAsIfNeverStopped) {
  // Stopped within Newton/CG (the predicate turns true on its 40th question, mid-step) and
  // between steps, then continued: the same enthalpies, bit for bit, and the same statistics
  // as a run never stopped.
  const GridProblem problem = build_grid_problem(
      parse_scenario_string("[simulation]\ngeometry = \"axisymmetric\"\nduration_s = 60.0\n"
                            "output_interval_s = 60.0\n\n[shape]\n"
                            "outer = { kind = \"sphere\", radius_m = 0.01 }\n"
                            "cavity = { kind = \"sphere\", radius_m = 0.006 }\n"
                            "[water]\ninitial_temperature_c = 10.0\n"
                            "[ice]\ninitial_temperature_c = -5.0\n[outer_boundary]\n"
                            "kind = \"convective\"\ntemperature_c = 25.0\n"
                            "heat_transfer_coefficient_w_m2k = 200.0\n",
                            "sphere.toml"));
  EnthalpySolver whole(problem);
  whole.advance_to(60);
  EnthalpySolver stopped(problem);
  int stops = 0;
  for (long asked = 0, at = 40; stopped.time() < 60 && !stopped.finished(); ++stops, at += 97) {
    const double before = stopped.time();
    stopped.advance_to(60, [&] { return ++asked >= at; });
    EXPECT_GE(stopped.time(), before);
    asked = 0;
  }
  EXPECT_GT(stops, 3);  // it was stopped several times on the way
  EXPECT_EQ(stopped.time(), whole.time());
  EXPECT_EQ(stopped.enthalpy(), whole.enthalpy());
  EXPECT_EQ(stopped.material_fraction(), whole.material_fraction());
  EXPECT_EQ(stopped.statistics().steps, whole.statistics().steps);
  EXPECT_EQ(stopped.statistics().newton_iterations, whole.statistics().newton_iterations);
  EXPECT_EQ(stopped.statistics().cg_iterations, whole.statistics().cg_iterations);
  EXPECT_EQ(stopped.events().size(), whole.events().size());
}

TEST(GridTimeStepper, SimulateThrowsInterruptedWithinASecondOfTheRequest) {
  // The interrupt flag (SIGINT, SIGTERM) raised from another thread while a grid run is inside
  // one output interval of 300 s: simulate() throws Interrupted, with or without a callback.
  const Scenario sc = hollow_cube("max_step_s = 0.01");
  for (bool with_callback : {true, false}) {
    clear_interrupt_request();
    std::atomic<long long> raised_ns{0};
    std::thread raiser([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
      raised_ns = Clock::now().time_since_epoch().count();
      request_interrupt();
    });
    const auto start = Clock::now();
    bool interrupted = false;
    try {
      if (with_callback) {
        simulate(sc, interruptible([](std::int64_t, std::int64_t) {}));
      } else {
        simulate(sc);
      }
    } catch (const Interrupted&) {
      interrupted = true;
    }
    const auto returned = Clock::now();
    raiser.join();
    clear_interrupt_request();
    EXPECT_TRUE(interrupted) << "with_callback " << with_callback;
    const double latency_s = std::chrono::duration<double>(returned.time_since_epoch() -
                                                           Clock::duration(raised_ns.load()))
                                 .count();
    EXPECT_LT(latency_s, 1.0) << "with_callback " << with_callback;
    EXPECT_LT(seconds_since(start), 30.0);
  }
}

TEST(GridTimeStepper, RunawayGuardEndsARunThatCouldNotFinish) {
  // Steps capped at 1e-5 s on a 1 cm sphere over an hour: 3.6e8 steps. The guard projects
  // that from its first window of work and throws, naming the cap as the cause.
  GridProblem problem = build_grid_problem(
      parse_scenario_string("[simulation]\ngeometry = \"axisymmetric\"\nduration_s = 3600.0\n"
                            "output_interval_s = 60.0\n\n[shape]\n"
                            "outer = { kind = \"sphere\", radius_m = 0.01 }\n"
                            "[ice]\ninitial_temperature_c = -5.0\n[outer_boundary]\n"
                            "kind = \"convective\"\ntemperature_c = 25.0\n"
                            "heat_transfer_coefficient_w_m2k = 50.0\n",
                            "sphere.toml"));
  problem.max_step_s = 1e-5;  // below the rules' floor: a problem built in code
  EnthalpySolver solver(problem);
  const auto start = Clock::now();
  try {
    solver.advance_to(60);
    FAIL() << "the guard let a run of 3.6e8 steps go on";
  } catch (const GridRunaway& e) {
    EXPECT_TRUE(e.at_max_step);
    EXPECT_NE(std::string(e.what()).find("would not end"), std::string::npos) << e.what();
  }
  EXPECT_LT(solver.time(), 1.0);
  EXPECT_LT(seconds_since(start), 60.0);
}

TEST(GridTimeStepper, RunawayThroughSimulateIsAUserErrorNamingTheKey) {
  // A cap the rules accept (above the floor) that still needs millions of steps of a large
  // grid: one line naming the file and simulation.max_step_s.
  try {
    simulate(hollow_cube("max_step_s = 0.0005"));
    FAIL() << "a run of 1.2e6 steps of 250000 cells was accepted";
  } catch (const UserError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cube.toml"), std::string::npos) << what;
    EXPECT_NE(what.find("simulation.max_step_s"), std::string::npos) << what;
    EXPECT_NE(what.find("would not end"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace thaw::sim
