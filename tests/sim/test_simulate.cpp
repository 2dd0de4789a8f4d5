// The library entry point (sim/simulate.h): output times land exactly on k * interval, an
// arbitrary list of times is honoured, and the written folder reads back through sim/io (the
// contract the mesher and inspector rely on).
#include "sim/simulate.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

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

/// A grid scenario of the bad-input campaign (issue 27): a hollow sphere or cube, 3600 s in
/// outputs of 0.0036 s (1e6 + 1, the rules' limit).
Scenario many_outputs_scenario(GridGeometry grid) {
  Scenario sc = parse_scenario_string(
      std::string("[simulation]\ngeometry = \"") +
          (grid == GridGeometry::axisymmetric ? "axisymmetric" : "3d") +
          "\"\nduration_s = 3600.0\noutput_interval_s = 0.0036\n"
          "[shape]\nouter = { kind = \"sphere\", radius_m = 0.02 }\n"
          "cavity = { kind = \"sphere\", radius_m = 0.012 }\n"
          "[water]\ninitial_temperature_c = 10.0\n[ice]\ninitial_temperature_c = -5.0\n"
          "[outer_boundary]\nkind = \"convective\"\ntemperature_c = 25.0\n"
          "heat_transfer_coefficient_w_m2k = 50.0\n",
      "many.toml");
  return sc;
}

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Issue 27: such a run kept every field in memory, grew ~68 MB/s and ended "out of memory",
// exit 3. Now it is refused before the first step, naming the key, the outputs and the bytes.
TEST(Simulate, GridFieldsThatCannotFitInMemoryAreRefusedUpFront) {
  const Scenario sc = many_outputs_scenario(GridGeometry::axisymmetric);
  const auto times = output_times(sc);
  ASSERT_EQ(times.size(), 1000001u);
  bool stepped = false;
  try {
    simulate(sc, times, [&](std::int64_t, std::int64_t) { stepped = true; });
    FAIL() << "kept 1e6 fields in memory";
  } catch (const UserError& e) {
    EXPECT_EQ(e.where(), "simulation.output_interval_s");
    EXPECT_NE(e.problem().find("1000001 outputs"), std::string::npos) << e.what();
    EXPECT_NE(e.problem().find("of memory"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(stepped);
}

// Streamed to disk, the same run is refused before the first field file when the files cannot
// fit on the disk (3D: ~1e5 cells, 1.2 MB per output, 1.2 TB in all).
TEST(Simulate, StreamedFieldsThatCannotFitOnTheDiskAreRefusedUpFront) {
  const Scenario sc = many_outputs_scenario(GridGeometry::cartesian3d);
  const auto times = output_times(sc);
  const fs::path dir = fresh_dir("many_outputs");
  bool stepped = false;
  try {
    simulate(
        sc, times, [&](std::int64_t, std::int64_t) { stepped = true; },
        field_stream(dir, sc, times.size()));
    FAIL() << "wrote 1e6 fields";
  } catch (const UserError& e) {
    EXPECT_EQ(e.where(), "simulation.output_interval_s");
    EXPECT_NE(e.problem().find("1000001 field files"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(stepped);
  EXPECT_FALSE(fs::exists(dir / "fields" / "step_000000.grid"));
}

// Streamed fields are the very bytes of fields kept in memory and written at the end.
TEST(Simulate, StreamedFieldsEqualFieldsKeptInMemory) {
  Scenario sc = many_outputs_scenario(GridGeometry::axisymmetric);
  sc.duration_s = 60;
  sc.output_interval_s = 20;
  sc.cell_size_m = 0.0025;
  sc.natural_convection = false;  // 2.5 mm cells are too coarse for the water's flow
  const fs::path kept = fresh_dir("fields_kept"), streamed = fresh_dir("fields_streamed");
  const SimulationResult a = simulate(sc);
  write_simulation_outputs(kept, a);
  const SimulationResult b =
      simulate(sc, output_times(sc), {}, field_stream(streamed, sc, output_times(sc).size()));
  EXPECT_TRUE(b.fields.empty());
  write_simulation_outputs(streamed, b);
  ASSERT_EQ(a.fields.size(), 4u);
  for (const char* f : {"interfaces.csv", "fields/step_000000.grid", "fields/step_000003.grid"})
    EXPECT_EQ(bytes_of(kept / f), bytes_of(streamed / f)) << f;
  EXPECT_FALSE(fs::exists(streamed / "fields" / "step_000004.grid"));
  const auto grid_of = [](const fs::path& dir) {
    std::ifstream js(dir / "summary.json");
    return nlohmann::json::parse(js).at("solver").at("grid");
  };
  EXPECT_EQ(grid_of(kept), grid_of(streamed));
}

}  // namespace
}  // namespace thaw::sim
