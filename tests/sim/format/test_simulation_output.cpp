// The result folder's guard (sim/format/simulation_output.h, foreign_entry): what may be replaced.
#include "sim/format/simulation_output.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "sim/format/scenario_file.h"

namespace thaw::sim {
namespace {

namespace fs = std::filesystem;

// Found by the bad-input sweep's review: `thaw simulate --out DIR` replaced DIR as a whole, so a
// folder of one's own given by mistake (`--out .`) lost every file in it.
TEST(SimulationOutput, OnlyAResultFolderOrAnEmptyOneMayBeReplaced) {
  const fs::path dir =
      fs::temp_directory_path() / ("thaw_simulation_output_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  EXPECT_EQ(foreign_entry(dir), std::nullopt);  // missing
  fs::create_directories(dir);
  EXPECT_EQ(foreign_entry(dir), std::nullopt);  // empty
  for (const char* own : {"interfaces.csv", "summary.json", "boundary_heat.csv"})
    std::ofstream(dir / own).close();
  for (const char* own : {"profiles", "fields", "mesh", "mesh.partial", "mesh.tmp-123-4"})
    fs::create_directories(dir / own);
  EXPECT_EQ(foreign_entry(dir), std::nullopt);  // a previous result, meshed
  std::ofstream(dir / "notes.txt").close();
  EXPECT_EQ(foreign_entry(dir), "notes.txt");
  fs::remove_all(dir);
}

/// boundary_heat.csv of a short grid run of `shape` (a [shape] outer table), parsed: per output
/// time, per face, the mean heat flow [W].
struct BoundaryHeat {
  SimulationResult result;
  std::vector<std::string> faces;  ///< in the file's row order
  std::map<double, std::map<std::string, double>> rows;
};
BoundaryHeat boundary_heat_of(const std::string& geometry, const std::string& shape) {
  const std::string text = "[simulation]\ngeometry = \"" + geometry +
                           "\"\nduration_s = 40.0\noutput_interval_s = 10.0\n"
                           "cell_size_m = 0.001\n[shape]\nouter = " +
                           shape +
                           "\n[water]\ninitial_temperature_c = 5.0\n[ice]\n"
                           "initial_temperature_c = -5.0\n[outer_boundary]\nkind = "
                           "\"convective\"\ntemperature_c = 20.0\n"
                           "heat_transfer_coefficient_w_m2k = 100.0\n";
  const Scenario sc = parse_scenario_string(text, "faces.toml");
  BoundaryHeat b;
  b.result = simulate(sc, output_times(sc));
  std::istringstream csv(format_boundary_heat_csv(b.result));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "time_s,face,heat_flow_w");
  while (std::getline(csv, line)) {
    const std::size_t a = line.find(','), c = line.rfind(',');
    const std::string face = line.substr(a + 1, c - a - 1);
    if (b.rows.empty() || b.rows.size() == 1)
      if (std::find(b.faces.begin(), b.faces.end(), face) == b.faces.end()) b.faces.push_back(face);
    b.rows[std::stod(line.substr(0, a))][face] = std::stod(line.substr(c + 1));
  }
  return b;
}

/// The file's heat, summed over the faces and times the interval, is the energy balance's
/// boundary heat (heat_in_j of the snapshots, which closes E - E0 - heat_in + drained to the
/// solver's 1e-8 per step): to the rounding of the sums (1e-12 of the heat).
void expect_sums_match_the_energy_balance(const BoundaryHeat& b) {
  const std::vector<Snapshot>& s = b.result.snapshots;
  ASSERT_EQ(b.rows.size() + 1, s.size());
  for (std::size_t k = 1; k < s.size(); ++k) {
    const auto& row = b.rows.at(s[k].time_s);
    double sum = 0;
    for (const auto& [face, w] : row) sum += w;
    const double heat = s[k].heat_in_j - s[k - 1].heat_in_j;
    EXPECT_GT(heat, 0);
    EXPECT_NEAR(sum * (s[k].time_s - s[k - 1].time_s), heat, 1e-12 * heat) << s[k].time_s;
    EXPECT_LT(std::abs(s[k].enthalpy_j - s[0].enthalpy_j - s[k].heat_in_j + s[k].drained_j),
              1e-8 * b.result.reference_energy_j);
  }
}

TEST(SimulationOutput, BoundaryHeatOfABoxByFaceSumsToTheEnergyBalance) {
  const BoundaryHeat b =
      boundary_heat_of("3d", "{ kind = \"box\", size_m = [0.012, 0.008, 0.010] }");
  EXPECT_EQ(b.faces,
            (std::vector<std::string>{"x_min", "x_max", "y_min", "y_max", "z_min", "z_max"}));
  expect_sums_match_the_energy_balance(b);
  // Conduction in a box in uniform air: mirror faces take the same heat (the grid is mirror
  // symmetric: rounding only), and the larger faces more (an edge's cells split between its two
  // faces by the surface's normal): y faces 12 x 10 mm, z faces 12 x 8 mm, x faces 8 x 10 mm.
  for (const auto& [t, row] : b.rows) {
    EXPECT_NEAR(row.at("x_min"), row.at("x_max"), 1e-9 * row.at("x_max")) << t;
    EXPECT_NEAR(row.at("y_min"), row.at("y_max"), 1e-9 * row.at("y_max")) << t;
    EXPECT_NEAR(row.at("z_min"), row.at("z_max"), 1e-9 * row.at("z_max")) << t;
    EXPECT_GT(row.at("y_min"), row.at("z_min"));  // 12 x 10 against 12 x 8 mm
    EXPECT_GT(row.at("z_min"), row.at("x_min"));  // 12 x 8 against 8 x 10 mm
  }
}

// A cube's six faces are alike: the split by the normal treats the axes alike (a split by
// position gave the edges to the first axis: x faces took 2x the z faces' heat).
TEST(SimulationOutput, BoundaryHeatOfACubeIsTheSameOnEveryFace) {
  const BoundaryHeat b = boundary_heat_of("3d", "{ kind = \"box\", size_m = [0.01, 0.01, 0.01] }");
  for (const auto& [t, row] : b.rows)
    for (const auto& [face, w] : row) EXPECT_NEAR(w, row.at("x_min"), 1e-6 * w) << t << face;
}

TEST(SimulationOutput, BoundaryHeatOfACylinderAndASphere) {
  const BoundaryHeat c = boundary_heat_of(
      "axisymmetric", "{ kind = \"cylinder\", radius_m = 0.006, height_m = 0.010 }");
  EXPECT_EQ(c.faces, (std::vector<std::string>{"top", "bottom", "side"}));
  expect_sums_match_the_energy_balance(c);
  for (const auto& [t, row] : c.rows) {
    EXPECT_NEAR(row.at("top"), row.at("bottom"), 1e-9 * row.at("top")) << t;
    // side 2 pi r h = 377 mm^2 against the ends' pi r^2 = 113 mm^2 each
    EXPECT_GT(row.at("side"), 2 * row.at("top"));
  }
  const BoundaryHeat s =
      boundary_heat_of("axisymmetric", "{ kind = \"sphere\", radius_m = 0.006 }");
  EXPECT_EQ(s.faces, (std::vector<std::string>{"surface"}));
  expect_sums_match_the_energy_balance(s);
}

}  // namespace
}  // namespace thaw::sim
