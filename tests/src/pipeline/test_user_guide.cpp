// Docs that cannot drift (issue 27): every figure of docs/user-guide.md that the program can
// produce is checked here against the program itself: the default scenario's shell, temperatures,
// air stream and break-through time (simulated), the [film] key table's defaults, the default
// film's frames and sample counts. A change of the default fails this test until the guide says
// the same. (The guide's file table is checked against a real run folder by test_pipeline.cpp;
// its command lines run in CTest: tests/src/cli/doc_commands.sh.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "base/number_text.h"
#include "sim/simulate.h"
#include "src/pipeline/run_scenario.h"

namespace thaw::pipeline {
namespace {

std::string read_doc(const char* name) {
  std::ifstream in(std::filesystem::path(THAW_SOURCE_DIR) / name);
  std::stringstream s;
  s << in.rdbuf();
  // Markdown wraps lines: compare the text with every line break as a space.
  std::string text = s.str();
  for (char& c : text)
    if (c == '\n') c = ' ';
  return text;
}

std::string cm(double metres) {
  return shortest_text(std::round(metres * 1e4) / 100);
}

void expect_says(const std::string& doc, const std::string& part) {
  EXPECT_NE(doc.find(part), std::string::npos) << "docs/user-guide.md should say: " << part;
}

TEST(UserGuide, TheDefaultScenarioAsTheGuideDescribesIt) {
  const std::string guide = read_doc("docs/user-guide.md");
  const RunScenario sc = default_run_scenario();
  const sim::Scenario& s = sc.simulation;
  expect_says(guide, "a hollow ice sphere (" + cm(s.outer_radius_m) + " cm outer, " +
                         cm(s.inner_radius_m) + " cm inner radius) at " +
                         shortest_text(s.ice_initial_temperature_c) + " C holding water at " +
                         shortest_text(s.water_initial_temperature_c) + " C");
  expect_says(guide, "in a " + shortest_text(s.outer_temperature_c) + " C air stream (h = " +
                         shortest_text(s.heat_transfer_coefficient_w_m2k) + " W/m^2/K)");
  // The break-through time, simulated.
  const sim::SimulationResult result = sim::simulate(s);
  double through = -1;
  for (const auto& e : result.events)
    if (e.kind == "break_through") through = e.time_s;
  ASSERT_GT(through, 0);
  char minutes[32];
  std::snprintf(minutes, sizeof minutes, "%.1f", through / 60);
  expect_says(guide, std::string("it breaks through after about ") + minutes + " minutes");
}

TEST(UserGuide, FilmKeyDefaultsAreTheParsersDefaults) {
  const std::string guide = read_doc("docs/user-guide.md");
  const FilmSettings unset;  // what [film] gives for a key left out
  expect_says(guide, "`fps` (" + shortest_text(unset.fps) + ";");
  expect_says(guide, "`frames` (" + std::to_string(unset.frames) + ";");
  expect_says(guide, std::string("`gif` (") + (unset.gif ? "true" : "false") + ")");
  expect_says(guide, std::string("`caption` (") + (unset.caption ? "true" : "false") + ")");
}

TEST(UserGuide, TheDefaultFilmsFramesAndSamples) {
  const std::string guide = read_doc("docs/user-guide.md");
  const RunScenario sc = default_run_scenario();
  const auto& image = sc.scene.image;
  // The frames filmed: the frame times the simulation reaches before the ice is gone.
  const std::size_t filmed = sim::simulate(sc.simulation, frame_times(sc)).snapshots.size();
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.1f s", static_cast<double>(filmed) / sc.film.fps);
  expect_says(guide, "The default film (" + std::to_string(frame_times(sc).size()) +
                         " frame times at " + shortest_text(sc.film.fps) + " fps, " +
                         std::to_string(image.width) + "x" + std::to_string(image.height) +
                         ", adaptive anti-aliasing from " + std::to_string(image.min_samples) +
                         " to " + std::to_string(image.samples_per_pixel) +
                         " samples per pixel, of which the " + std::to_string(filmed) +
                         " frame times before the break-through are filmed: " + seconds);
}

}  // namespace
}  // namespace thaw::pipeline
