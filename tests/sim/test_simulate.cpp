// The library entry point (sim/simulate.h): output times land exactly on k * interval, an
// arbitrary list of times is honoured, and the written folder reads back through sim/io (the
// contract the mesher and inspector rely on).
#include "sim/simulate.h"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "base/error.h"
#include "sim/format/interface_history.h"
#include "sim/format/scenario_file.h"
#include "sim/format/simulation_output.h"

namespace thaw::sim {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(THAW_BINARY_DIR) / "test-tmp" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(Simulate, OutputTimesAreExactMultiplesOfTheInterval) {
  Scenario sc = default_scenario();
  sc.duration_s = 1.0;
  sc.output_interval_s = 0.1;
  const auto times = output_times(sc);
  ASSERT_EQ(times.size(), 11u);
  for (std::size_t k = 0; k < times.size(); ++k) EXPECT_EQ(times[k], std::min(k * 0.1, 1.0));
  sc.output_interval_s = 0.3;  // duration not a multiple: the end time is added
  const auto t2 = output_times(sc);
  ASSERT_EQ(t2.size(), 5u);
  EXPECT_EQ(t2[3], 3 * 0.3);
  EXPECT_EQ(t2.back(), 1.0);
}

TEST(Simulate, SamplesExactlyAtArbitraryRequestedTimes) {
  const Scenario sc = default_scenario();
  const std::vector<double> times = {0.0, 1.0 / 3.0, 7.25, 100.0 / 7.0, 600.0};
  const SimulationResult r = simulate(sc, times);
  ASSERT_EQ(r.snapshots.size(), times.size());
  for (std::size_t i = 0; i < times.size(); ++i) EXPECT_EQ(r.snapshots[i].time_s, times[i]);
  EXPECT_FALSE(r.ended_early);
  EXPECT_THROW(simulate(sc, {0.0, 2.0, 1.0}), UserError);
  EXPECT_THROW(simulate(sc, std::vector<double>{}), UserError);
  EXPECT_THROW(simulate(sc, {-1.0, 2.0}), UserError);
}

TEST(Simulate, RunEndsAtBreakThroughWithOneLastRow) {
  const Scenario sc = default_scenario();
  const SimulationResult r = simulate(sc);
  ASSERT_TRUE(r.ended_early);
  ASSERT_FALSE(r.events.empty());
  EXPECT_EQ(r.events.back().kind, "break_through");
  EXPECT_EQ(r.snapshots.back().time_s, r.events.back().time_s);
  for (std::size_t i = 0; i + 1 < r.snapshots.size(); ++i)
    EXPECT_EQ(r.snapshots[i].time_s, static_cast<double>(i) * sc.output_interval_s);
}

TEST(Simulate, FirstRowIsTheInitialStateEvenWithAnAnalyticStart) {
  // A water drop with no ice yet: the ice is started from the Neumann solution at t0 > 0, but
  // the row at t = 0 must show no ice (inner == outer), the next rows a growing shell.
  const Scenario sc =
      read_scenario_file(std::string(THAW_SOURCE_DIR) + "/data/scenarios/water_drop_freezing.toml");
  const SimulationResult r = simulate(sc);
  ASSERT_GT(r.statistics.start_time_s, 0.0);
  EXPECT_EQ(r.snapshots[0].time_s, 0.0);
  EXPECT_EQ(r.snapshots[0].inner_radius_m, sc.inner_radius_m);
  EXPECT_EQ(r.snapshots[0].outer_radius_m, sc.outer_radius_m);
  EXPECT_EQ(r.snapshots[0].ice_volume_m3, 0.0);
  EXPECT_LT(r.snapshots[1].inner_radius_m, sc.inner_radius_m);
  for (const ProfilePoint& p : r.snapshots[0].profile)
    EXPECT_EQ(p.temperature_c, sc.water_initial_temperature_c);
}

TEST(Simulate, WrittenFolderReadsBackThroughTheSharedContract) {
  for (Geometry g : {Geometry::sphere, Geometry::cylinder, Geometry::planar}) {
    Scenario sc = default_scenario();
    sc.geometry = g;
    sc.duration_s = 300;
    const fs::path dir = fresh_dir(std::string("simulate_") + to_string(g));
    const SimulationResult r = simulate(sc);
    write_simulation_outputs(dir, r);
    const auto rows = read_interfaces_csv(dir / "interfaces.csv");
    ASSERT_EQ(rows.size(), r.snapshots.size());
    EXPECT_EQ(rows[3].time_s, 3 * sc.output_interval_s);
    EXPECT_EQ(rows[3].inner_radius_m, r.snapshots[3].inner_radius_m);  // 17 digits round-trip
    std::ifstream csv(dir / "interfaces.csv");
    std::string header;
    std::getline(csv, header);
    EXPECT_EQ(header.rfind("step,time_s,inner_radius_m,outer_radius_m,liquid_volume_m3,ice_volume_"
                           "m3,energy_balance_error",
                           0),
              0u);
    const ShellGeometry shell = read_shell_geometry(dir / "summary.json");
    EXPECT_EQ(shell.geometry, g);
    if (g == Geometry::cylinder) {
      EXPECT_EQ(shell.length_m, sc.length_m);
    }
    if (g == Geometry::planar) {
      EXPECT_EQ(shell.lateral_size_m, sc.lateral_size_m);
    }
    std::ifstream profile(dir / "profiles" / "step_000005.csv");
    std::string line;
    std::getline(profile, line);
    EXPECT_EQ(line, "r_m,temperature_c,phase");
    int water = 0, ice = 0;
    while (std::getline(profile, line)) {
      water += line.ends_with(",water");
      ice += line.ends_with(",ice");
    }
    EXPECT_GE(water, sc.cells_per_phase);
    EXPECT_GE(ice, sc.cells_per_phase);
    std::ifstream js(dir / "summary.json");
    const nlohmann::json j = nlohmann::json::parse(js);
    EXPECT_EQ(j.at("parameters").at("simulation").at("time_tolerance"), sc.time_tolerance);
    EXPECT_EQ(j.at("parameters").at("materials").at("latent_heat_j_kg"), 333400.0);
    EXPECT_TRUE(j.at("events").is_array());
    EXPECT_GT(j.at("solver").at("steps").get<long>(), 0);
    EXPECT_LT(j.at("solver").at("max_energy_balance_error").get<double>(), 1e-8);
    EXPECT_TRUE(j.contains("wall_time_s"));
  }
}

}  // namespace
}  // namespace thaw::sim
