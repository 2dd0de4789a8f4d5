// Whole grid runs through sim/simulate.h on small scenarios: break-through and draining, a
// cavity freezing shut (core_frozen, against the 1D sphere), symmetry, thread-count invariance,
// the OBJ sphere against the analytic sphere.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "sim/format/scenario_file.h"
#include "sim/format/simulation_output.h"
#include "sim/grid/enthalpy_solver.h"
#include "sim/grid/grid_builder.h"
#include "sim/simulate.h"

namespace thaw::sim {
namespace {

/// Conduction only (flow = "none"): these runs test the enthalpy solver (the flow's own tests:
/// tests/sim/flow, test_grid_flow.cpp).
std::string scenario_text(const std::string& geometry, const std::string& shape,
                          const std::string& extra_sim, double duration, double h) {
  return "[simulation]\ngeometry = \"" + geometry + "\"\nduration_s = " + std::to_string(duration) +
         "\noutput_interval_s = " + std::to_string(duration / 10) + "\nflow = \"none\"\n" +
         extra_sim + "\n[shape]\n" + shape +
         "\n[water]\ninitial_temperature_c = 10.0\n[ice]\ninitial_temperature_c = -5.0\n"
         "[outer_boundary]\nkind = \"convective\"\ntemperature_c = "
         "25.0\nheat_transfer_coefficient_w_m2k = " +
         std::to_string(h) + "\n";
}

const GridEvent* find_event(const SimulationResult& r, const std::string& kind) {
  for (const auto& e : r.grid_events)
    if (e.kind == kind) return &e;
  return nullptr;
}

TEST(GridRuns, ThinShellBreaksThroughDrainsAndGoesOn) {
  // A 1 cm sphere with a 0.8 cm cavity in a hot air stream: the 2 mm shell opens well within
  // the run; afterwards no liquid is enclosed, the cavity's water has drained, and the run
  // continues on the open shell (more ice melts after the event).
  const Scenario sc =
      parse_scenario_string(scenario_text("axisymmetric",
                                          "outer = { kind = \"sphere\", radius_m = 0.01 }\ncavity "
                                          "= { kind = \"sphere\", radius_m = 0.008 }",
                                          "", 1200, 200),
                            "thin_shell.toml");
  const SimulationResult r = simulate(sc);
  const GridEvent* bt = find_event(r, "break_through");
  ASSERT_NE(bt, nullptr);
  EXPECT_LT(r.grid_statistics.max_step_energy_error, 1e-8);
  // The event's position lies in the shell (between the two initial surfaces, one cell slack).
  const double radius = std::hypot(bt->position_m[0], bt->position_m[1]);
  EXPECT_GT(radius, 0.008 - 0.0005);
  EXPECT_LT(radius, 0.01 + 0.0005);
  bool after = false;
  double ice_before_event = 0;
  for (const Snapshot& s : r.snapshots) {
    if (s.time_s < bt->time_s) {
      ice_before_event = s.ice_volume_m3;
      continue;
    }
    if (!after) {
      after = true;
      // drained: less than 1 % of the initial cavity volume is still liquid
      EXPECT_LT(s.liquid_volume_m3, 0.01 * (4.0 / 3.0) * std::numbers::pi * std::pow(0.008, 3));
    }
  }
  ASSERT_TRUE(after);  // rows after the event: the run went on
  EXPECT_GT(r.snapshots.back().time_s, bt->time_s);
  EXPECT_LT(r.snapshots.back().ice_volume_m3, ice_before_event);  // and went on melting
  for (const Snapshot& s : r.snapshots) EXPECT_LT(s.energy_balance_error, 1e-8);
}

TEST(GridRuns, CavityFreezesShutLikeThe1dSphere) {
  // A 1 cm ice sphere at -20 C held at -20 C on its surface, with a 5 mm cavity of water at
  // 1 C: the cavity freezes shut. The grid run (axisymmetric, default cells) must record
  // core_frozen inside the cavity, go on after it with no liquid left, write the event with its
  // position to summary.json, and follow the 1D sphere's solution (the same physics).
  const std::string common =
      "[water]\ninitial_temperature_c = 1.0\n[ice]\ninitial_temperature_c = -20.0\n"
      "[outer_boundary]\nkind = \"temperature\"\ntemperature_c = -20.0\n";
  const double duration = 300, interval = 5;
  const std::string sim = "[simulation]\nduration_s = " + std::to_string(duration) +
                          "\noutput_interval_s = " + std::to_string(interval) + "\n";
  const SimulationResult one = simulate(parse_scenario_string(
      sim + "geometry = \"sphere\"\n[shell]\ninner_radius_m = 0.005\nouter_radius_m = 0.01\n" +
          common,
      "one.toml"));
  const SimulationResult g = simulate(parse_scenario_string(
      sim +
          "geometry = \"axisymmetric\"\nflow = \"none\"\n[shape]\nouter = { kind = \"sphere\", "
          "radius_m = 0.01 }\ncavity = { kind = \"sphere\", radius_m = 0.005 }\n" +
          common,
      "freeze.toml"));
  double t_one = -1;
  for (const Event& e : one.events)
    if (e.kind == "core_frozen") t_one = e.time_s;
  ASSERT_GT(t_one, 0) << "the 1D sphere must freeze shut within the run";
  const GridEvent* frozen = find_event(g, "core_frozen");
  ASSERT_NE(frozen, nullptr);
  EXPECT_EQ(find_event(g, "break_through"), nullptr);
  // Where the last liquid was: inside the initial cavity (one cell of slack).
  const double cell = g.fields.front().spacing_m;
  EXPECT_LT(std::hypot(frozen->position_m[0], frozen->position_m[1]), 0.005 + cell);
  // The run goes on after the event, with no liquid left.
  ASSERT_GT(g.snapshots.back().time_s, frozen->time_s);
  EXPECT_EQ(g.snapshots.back().liquid_volume_m3, 0.0);
  EXPECT_LT(g.grid_statistics.max_step_energy_error, 1e-8);
  // The liquid volume follows the 1D solution within 1 % of the initial ice volume (the issue's
  // bar for the sphere at default resolution). So the grid's core freezes when the 1D core
  // holds at most that much: between the 1D instant at which 1 % of V_ice(0) is still liquid
  // (rows interpolated linearly) and the 1D core_frozen plus the same span, plus one output
  // interval (the grid's event is found at the end of a step, at most max_step_s = 10 s after
  // the last liquid froze, which is more than an interval here).
  const double v0 = one.snapshots.front().ice_volume_m3, bar = 0.01 * v0;
  double t_bar = 0;
  for (std::size_t i = 1; i < one.snapshots.size(); ++i) {
    const Snapshot &a = one.snapshots[i - 1], &b = one.snapshots[i];
    if (i < g.snapshots.size() && b.time_s <= t_one) {
      EXPECT_NEAR(g.snapshots[i].liquid_volume_m3, b.liquid_volume_m3, bar) << b.time_s;
    }
    if (a.liquid_volume_m3 > bar && b.liquid_volume_m3 <= bar)
      t_bar = a.time_s + (b.time_s - a.time_s) * (a.liquid_volume_m3 - bar) /
                             (a.liquid_volume_m3 - b.liquid_volume_m3);
  }
  ASSERT_GT(t_bar, 0);
  const double window = (t_one - t_bar) + std::max(interval, 10.0);
  std::printf("core_frozen: grid %.1f s, 1D %.1f s (1 %% of V0 liquid at %.1f s), window %.1f s\n",
              frozen->time_s, t_one, t_bar, window);
  EXPECT_NEAR(frozen->time_s, t_one, window);
  // summary.json carries the event with its time and position
  const std::filesystem::path dir =
      std::filesystem::path(testing::TempDir()) / "thaw_grid_core_frozen";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  write_simulation_outputs(dir, g);
  std::ifstream js(dir / "summary.json");
  const nlohmann::json j = nlohmann::json::parse(js);
  bool written = false;
  for (const auto& e : j.at("events"))
    if (e.at("kind") == "core_frozen") {
      written = true;
      EXPECT_EQ(e.at("time_s").get<double>(), frozen->time_s);
      EXPECT_EQ(e.at("position_m").get<std::vector<double>>(),
                std::vector<double>(frozen->position_m.begin(), frozen->position_m.end()));
    }
  EXPECT_TRUE(written);
  std::filesystem::remove_all(dir);
}

TEST(GridRuns, SymmetricCubeGivesSymmetricFields) {
  const Scenario sc =
      parse_scenario_string(scenario_text("3d",
                                          "outer = { kind = \"box\", size_m = [0.02, 0.02, 0.02] "
                                          "}\ncavity = { kind = \"box\", size_m = "
                                          "[0.012, 0.012, 0.012] }",
                                          "cell_size_m = 0.001", 120, 50),
                            "cube.toml");
  const SimulationResult r = simulate(sc);
  const GridField& f = r.fields.back();
  ASSERT_EQ(f.cells[0], f.cells[2]);
  double worst = 0;
  const int n = f.cells[0];
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < f.cells[1]; ++j)
      for (int i = 0; i < n; ++i) {
        const float t = f.temperature_c[f.index(i, j, k)];
        // mirror in x, mirror in z, swap x and z: all symmetries of the cube about the y axis
        for (std::size_t other :
             {f.index(n - 1 - i, j, k), f.index(i, j, n - 1 - k), f.index(k, j, i)}) {
          worst = std::max(worst, static_cast<double>(std::abs(t - f.temperature_c[other])));
          worst = std::max(worst, static_cast<double>(std::abs(f.ice_fraction[f.index(i, j, k)] -
                                                               f.ice_fraction[other])));
        }
      }
  // round-off of the sums' order, seen through float output: a few float ulps of 25 C
  EXPECT_LT(worst, 1e-5);
}

TEST(GridRuns, SymmetricCubeIsSymmetricToRoundOffInEveryCell) {
  // The solver's own doubles (enthalpy and material fraction of every cell), compared with their
  // images under the cube's mirrors in x, y and z and the swaps x<->y, x<->z (no gravity: y is
  // as symmetric as x). Mirrored cells run the same operations in another order (stencil sums,
  // block sums of the CG), so they may differ by round-off only: a few ulps per operation,
  // ~1e3 operations per cell and step through the coupled CG, ~100 steps -> far below 1e-9 of
  // the enthalpy scale L_v and of a fraction; a real asymmetry (an index off by one, a one-sided
  // stencil) is O(1) in the cells it touches.
  const Scenario sc =
      parse_scenario_string(scenario_text("3d",
                                          "outer = { kind = \"box\", size_m = [0.02, 0.02, 0.02] "
                                          "}\ncavity = { kind = \"box\", size_m = "
                                          "[0.012, 0.012, 0.012] }",
                                          "cell_size_m = 0.001", 120, 50),
                            "cube.toml");
  const GridProblem problem = build_grid_problem(sc);
  const int n = problem.cells[0];
  ASSERT_EQ(problem.cells[1], n);
  ASSERT_EQ(problem.cells[2], n);
  EnthalpySolver solver(problem);
  solver.advance_to(120);
  ASSERT_GT(solver.statistics().steps, 10);
  const std::vector<double>& h = solver.enthalpy();
  const std::vector<double>& m = solver.material_fraction();
  const double latent = problem.materials.latent_heat_per_volume();
  auto at = [&](int i, int j, int k) { return static_cast<std::size_t>(i + n * (j + n * k)); };
  double worst_h = 0, worst_m = 0;
  int drained = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::size_t c = at(i, j, k);
        drained += m[c] > 0 && m[c] < 1;
        for (std::size_t o : {at(n - 1 - i, j, k), at(i, n - 1 - j, k), at(i, j, n - 1 - k),
                              at(j, i, k), at(k, j, i)}) {
          worst_h = std::max(worst_h, std::abs(h[c] - h[o]) / latent);
          worst_m = std::max(worst_m, std::abs(m[c] - m[o]));
        }
      }
  std::printf("symmetry: largest difference %.2e L_v in enthalpy, %.2e in fraction\n", worst_h,
              worst_m);
  EXPECT_GT(drained, 0);  // the surface has ablated: draining is part of what is checked
  EXPECT_LT(worst_h, 1e-9);
  EXPECT_LT(worst_m, 1e-9);
}

TEST(GridRuns, ResultsDoNotDependOnTheThreadCount) {
  // 30^3 cells: above the solver's threshold for a parallel step. An off-centre cavity (no
  // symmetry to hide a race) and 1, 2 and 3 threads (3 splits the 7 blocks unevenly): the
  // enthalpy of every cell and the statistics agree bit for bit.
  const Scenario sc =
      parse_scenario_string(scenario_text("3d",
                                          "outer = { kind = \"sphere\", radius_m = 0.013 }\ncavity "
                                          "= { kind = \"sphere\", radius_m = "
                                          "0.008, center_m = [0.001, 0.0, 0.0] }",
                                          "cell_size_m = 0.001", 30, 50),
                            "threads.toml");
  const int saved = omp_get_max_threads();
  std::vector<std::vector<double>> enthalpy;
  std::vector<GridStatistics> stats;
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    EnthalpySolver solver(build_grid_problem(sc));
    ASSERT_GT(solver.enthalpy().size(), 16384u);
    solver.advance_to(30);
    enthalpy.push_back(solver.enthalpy());
    stats.push_back(solver.statistics());
  }
  omp_set_num_threads(saved);
  for (std::size_t r = 1; r < enthalpy.size(); ++r) {
    EXPECT_TRUE(enthalpy[r] == enthalpy[0]) << r + 1 << " threads";
    EXPECT_EQ(stats[r].steps, stats[0].steps);
    EXPECT_EQ(stats[r].newton_iterations, stats[0].newton_iterations);
    EXPECT_EQ(stats[r].cg_iterations, stats[0].cg_iterations);
  }
  EXPECT_GT(stats[0].cg_iterations, 0);
}

TEST(GridRuns, ObjSphereMatchesTheAnalyticSphere) {
  // data/shapes/icosphere.obj scaled to 1.2 cm against the analytic sphere of the same volume
  // (the icosphere encloses 4.15274 of the unit ball's 4.18879): after five minutes of
  // melting, ice volumes agree within 1 % of the initial volume (the OBJ cells use a linear
  // fraction ramp instead of sub-sampling, and the facets differ from the sphere by < 0.3 % in
  // radius).
  const std::string obj = std::string(THAW_SOURCE_DIR) + "/data/shapes/icosphere.obj";
  const double r_eq = 0.012 * std::cbrt(4.152740817093066 / (4.0 / 3.0 * std::numbers::pi));
  const Scenario a = parse_scenario_string(
      scenario_text("3d", "outer = { kind = \"obj\", file = \"" + obj + "\", scale = 0.012 }",
                    "cell_size_m = 0.001", 300, 50),
      "obj.toml");
  const Scenario b = parse_scenario_string(
      scenario_text("3d", "outer = { kind = \"sphere\", radius_m = " + std::to_string(r_eq) + " }",
                    "cell_size_m = 0.001", 300, 50),
      "sphere.toml");
  const SimulationResult ra = simulate(a), rb = simulate(b);
  const double v0 = rb.snapshots.front().ice_volume_m3;
  EXPECT_NEAR(ra.snapshots.front().ice_volume_m3, v0, 0.005 * v0);
  for (std::size_t i = 0; i < ra.snapshots.size(); ++i)
    EXPECT_NEAR(ra.snapshots[i].ice_volume_m3, rb.snapshots[i].ice_volume_m3, 0.01 * v0) << i;
}

}  // namespace
}  // namespace thaw::sim

namespace thaw::sim {
namespace {

TEST(GridRuns, FreeIceSphereInRoomAirMeltsAsThe1dSolver) {
  // [outer_boundary] kind = "air" on the grid: a 2 cm radius ice sphere at T_m in air at 20 C,
  // 50 %, still and at 2 m/s, axisymmetric at 1 mm cells. The grid takes the air's flux at a
  // sphere of its current volume, the 1D solver at its radius: the same body. The melt times
  // agree within the grid's ablation-area error (about 1 % of the depth at 0.125-0.5 mm cells,
  // docs/validation.md) plus one step of the event's resolution (max_step_s / t).
  for (const char* speed : {"0.0", "2.0"}) {
    const std::string body = std::string(R"(
[simulation]
geometry = "@G"
duration_s = 20000.0
output_interval_s = 1000.0
@CELLS
[@BODY]
@SHAPE
[water]
initial_temperature_c = 0.0
[ice]
initial_temperature_c = 0.0
[outer_boundary]
kind = "air"
temperature_c = 20.0
relative_humidity = 0.5
speed_m_s = )") + speed + "\n";
    auto make = [&](bool grid) {
      std::string t = body;
      auto put = [&](const std::string& key, const std::string& value) {
        t.replace(t.find(key), key.size(), value);
      };
      put("@G", grid ? "axisymmetric" : "sphere");
      put("@CELLS", grid ? "cell_size_m = 1e-3\nmax_step_s = 20.0" : "cells_per_phase = 16");
      put("@BODY", grid ? "shape" : "shell");
      put("@SHAPE", grid ? "outer = { kind = \"sphere\", radius_m = 0.02 }"
                         : "inner_radius_m = 0.0\nouter_radius_m = 0.02");
      return parse_scenario_string(t, grid ? "grid_air.toml" : "radial_air.toml");
    };
    const SimulationResult grid = simulate(make(true));
    const SimulationResult radial = simulate(make(false));
    const GridEvent* melted = find_event(grid, "fully_melted");
    ASSERT_NE(melted, nullptr) << speed;
    double t1d = -1;
    for (const Event& e : radial.events)
      if (e.kind == "fully_melted") t1d = e.time_s;
    ASSERT_GT(t1d, 0) << speed;
    std::printf("  air %s m/s: grid melted at %.0f s, 1D at %.1f s (%+.2f %%)\n", speed,
                melted->time_s, t1d, 100 * (melted->time_s / t1d - 1));
    EXPECT_NEAR(melted->time_s, t1d, 0.01 * t1d + 20.0) << speed;
    EXPECT_LT(grid.grid_statistics.max_step_energy_error, 1e-8);
  }
}

/// Fraction of a sphere's volume below the height y_over_r (in radii) from its centre.
double sphere_below(double y_over_r) {
  const double y = std::clamp(y_over_r, -1.0, 1.0);
  return 0.5 + 0.75 * y - 0.25 * y * y * y;
}

TEST(GridRuns, OpenShellHoldsItsWaterUpToTheOpening) {
  // A 1 cm ice sphere whose 6 mm cavity sits 2.4 mm towards +x: its thinnest wall (1.6 mm) is
  // the side at mid-height, so the shell opens there and the cup keeps the water below the
  // hole (issue 25 item 1): about half, as a sphere cut at its equator; water above the level
  // drains, the level drops as the hole melts downwards, and the books balance at every
  // output: ice + liquid + drained = the initial material (one density for ice and water).
  const Scenario sc = parse_scenario_string(
      "[simulation]\ngeometry = \"3d\"\nduration_s = 120.0\noutput_interval_s = 20.0\n"
      "cell_size_m = 0.0005\nflow = \"none\"\n[shape]\nouter = { kind = \"sphere\", "
      "radius_m = 0.01 }\n"
      "cavity = { kind = \"sphere\", radius_m = 0.006, center_m = [0.0024, 0.0, 0.0] }\n"
      "[water]\ninitial_temperature_c = 10.0\n[ice]\ninitial_temperature_c = -1.0\n"
      "[outer_boundary]\nkind = \"convective\"\ntemperature_c = 40.0\n"
      "heat_transfer_coefficient_w_m2k = 200.0\n",
      "side_hole.toml");
  const GridEvent* first = nullptr;
  const SimulationResult coarse = simulate(sc);
  first = find_event(coarse, "break_through");
  ASSERT_NE(first, nullptr);
  // again with outputs every second around the opening
  std::vector<double> times{0};
  for (double t = std::floor(first->time_s) - 10; t < first->time_s + 10; t += 1)
    times.push_back(t);
  times.push_back(120);
  const SimulationResult r = simulate(sc, times);
  const GridEvent* bt = find_event(r, "break_through");
  ASSERT_NE(bt, nullptr);
  const double dx = r.fields.front().spacing_m;
  std::printf("break_through at %.1f s, (%.4f, %.4f, %.4f) m\n", bt->time_s, bt->position_m[0],
              bt->position_m[1], bt->position_m[2]);
  int drops = 0;
  for (const GridEvent& e : r.grid_events)
    if (e.kind == "water_level_drop") ++drops;
  std::printf("%d water_level_drop events\n", drops);
  EXPECT_GT(bt->position_m[0], 0.006);  // the +x side
  // within 2 mm of mid-height: the wall there is thicker than at the equator by only
  // y^2 / 2 (1 / 6 mm - 1 / 10 mm) = 0.13 mm, a quarter cell, so the hole may open anywhere in it
  EXPECT_LT(std::abs(bt->position_m[1]), 4 * dx);
  EXPECT_GT(drops, 0);
  // the books, every output
  const auto& w = r.water_records;
  ASSERT_EQ(w.size(), r.snapshots.size());
  const double v0 = w.front().ice_m3 + w.front().liquid_m3;
  for (const auto& row : w)
    EXPECT_NEAR(row.ice_m3 + row.liquid_m3 + row.drained_m3, v0, 1e-9 * v0) << row.time_s;
  // the first output after the opening holds the cavity's water below the level
  std::size_t k = 2;
  while (k < w.size() && w[k].time_s < bt->time_s) ++k;
  ASSERT_LT(k + 1, w.size()) << "the run must go on after the opening";
  ASSERT_TRUE(std::isfinite(w[k].level_m));
  // the level is that of the last opening (break-through or drop) before the output
  double level = bt->position_m[1];
  for (const GridEvent& e : r.grid_events)
    if (e.kind == "water_level_drop" && e.time_s <= w[k].time_s) level = e.position_m[1];
  EXPECT_DOUBLE_EQ(w[k].level_m, level);
  std::printf("held %.3e m^3 at %.0f s (level %.5f m); enclosed before %.3e m^3 at %.0f s\n",
              w[k].held_m3, w[k].time_s, w[k].level_m, w[k - 1].enclosed_m3, w[k - 1].time_s);
  // The cavity is about a sphere of the volume enclosed before (grown from 6 mm), centred at
  // y = 0; the level cuts it. Slack: one cell of level over its equatorial area, plus what the
  // cavity gained in the second before the opening (the same again after it).
  const double enclosed = w[k - 1].enclosed_m3;
  const double radius = std::cbrt(3 * enclosed / (4 * std::numbers::pi));
  const double expected = enclosed * sphere_below(w[k].level_m / radius);
  const double slack = std::numbers::pi * radius * radius * dx +
                       2 * std::abs(w[k - 1].enclosed_m3 - w[k - 2].enclosed_m3);
  std::printf("expected %.3e +- %.1e m^3\n", expected, slack);
  EXPECT_NEAR(w[k].held_m3, expected, slack);
  EXPECT_GT(w[k].drained_m3 - w[k - 1].drained_m3, 0.3 * enclosed);  // the top half spilt
  // no water above the level in the field but the traces melting inside the ice
  const GridField& f = r.fields[k];
  double above = 0;
  for (int kk = 0; kk < f.cells[2]; ++kk)
    for (int j = 0; j < f.cells[1]; ++j)
      for (int i = 0; i < f.cells[0]; ++i)
        if (f.origin_m[1] + j * f.spacing_m >= w[k].level_m)
          above += f.water_fraction[f.index(i, j, kk)] * dx * dx * dx;
  EXPECT_LT(above, 0.01 * w[k].held_m3);
  EXPECT_LT(r.grid_statistics.max_step_energy_error, 1e-8);
}

}  // namespace
}  // namespace thaw::sim
