// Tests src/pipeline/run_scenario.h: [film] frames_format (issue 13): "png" by default, "exr"
// accepted, anything else a UserError naming the file and the key; [render.shell] placement
// (issue 12): a floor or centre too far out for single precision names its key.
#include "src/pipeline/run_scenario.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "base/error.h"
#include "base/format/toml_table.h"

namespace thaw::pipeline {
namespace {

/// The default scenario with `line` added to its [film] table.
RunScenario with_film_line(const std::string& line) {
  std::string text = default_run_scenario_text();
  const auto at = text.find("[film]\n");
  EXPECT_NE(at, std::string::npos);
  text.insert(at + 7, line + "\n");
  return parse_run_scenario(TomlTable::parse_string(text, "scenario.toml"));
}

TEST(RunScenario, FramesFormatDefaultsToPngAndAcceptsExr) {
  EXPECT_EQ(default_run_scenario().film.frames_format, FilmSettings::FramesFormat::png);
  EXPECT_EQ(with_film_line("frames_format = \"png\"").film.frames_format,
            FilmSettings::FramesFormat::png);
  EXPECT_EQ(with_film_line("frames_format = \"exr\"").film.frames_format,
            FilmSettings::FramesFormat::exr);
}

TEST(RunScenario, UnknownFramesFormatNamesFileAndKey) {
  try {
    with_film_line("frames_format = \"tiff\"");
    FAIL() << "no error";
  } catch (const UserError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("scenario.toml"), std::string::npos) << what;
    EXPECT_NE(what.find("frames_format"), std::string::npos) << what;
    EXPECT_NE(what.find("tiff"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  EXPECT_THROW(with_film_line("frames_format = 3"), UserError);
}

/// The default scenario with its [render.shell] line starting `key` replaced by `line`.
RunScenario with_shell_line(const std::string& key, const std::string& line) {
  std::string text = default_run_scenario_text();
  const auto at = text.find("\n" + key + " = ", text.find("[render.shell]"));
  EXPECT_NE(at, std::string::npos);
  text.replace(at + 1, text.find('\n', at + 1) - at - 1, line);
  return parse_run_scenario(TomlTable::parse_string(text, "scenario.toml"));
}

// Before: "shell outer surface: shell outer surface: a dielectric mesh must be oriented outward"
// at render time, after simulating and meshing.
TEST(RunScenario, FarFloorOrCentreNamesFileAndKey) {
  for (const auto& [line, key] :
       {std::pair{"floor_y = 2147483647", "floor_y"}, std::pair{"floor_y = -1e12", "floor_y"},
        std::pair{"center = [0.0, 0.0, 3e9]", "center"}}) {
    try {
      with_shell_line(key, line);
      ADD_FAILURE() << "accepted " << line;
    } catch (const UserError& e) {
      EXPECT_EQ(e.file(), "scenario.toml") << e.what();
      EXPECT_NE(e.where().find(std::string("render.shell.") + key), std::string::npos) << e.what();
      EXPECT_NE(e.problem().find("single precision"), std::string::npos) << e.what();
    }
  }
  // A 3 cm shell's mesh edges (2.5 mm) are still resolved 100 m up.
  EXPECT_EQ(with_shell_line("floor_y", "floor_y = 100.0").shell.floor_y, 100.0);
}

}  // namespace
}  // namespace thaw::pipeline

namespace thaw::pipeline {
namespace {

/// The default scenario with each `from` replaced by its `to`, parsed; the error's text, or "".
std::string parse_error(const std::vector<std::pair<std::string, std::string>>& edits) {
  std::string text = default_run_scenario_text();
  for (const auto& [from, to] : edits) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  try {
    parse_run_scenario(TomlTable::parse_string(text, "scenario.toml"));
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Issue 27 item 5: sizes typed in centimetres are refused when the scenario is read, naming the
// key, its line and the unit; no hint names an option thaw run does not have.
TEST(RunScenario, ABallInCentimetresIsRefusedNamingMetres) {
  const std::string e = parse_error({{"inner_radius_m = 0.02 ", "inner_radius_m = 2.0 "},
                                     {"outer_radius_m = 0.03 ", "outer_radius_m = 3.0 "}});
  const std::string text = default_run_scenario_text();
  const auto line =
      1 + std::count(text.begin(), text.begin() + text.find("outer_radius_m = "), '\n');
  EXPECT_TRUE(
      has(e, "scenario.toml: line " + std::to_string(line) + ", key 'shell.outer_radius_m'"))
      << e;
  EXPECT_TRUE(has(e, "3 m makes a piece 6 m across")) << e;
  EXPECT_TRUE(has(e, "the keys are in metres: 3 cm is 0.03")) << e;
  EXPECT_FALSE(has(e, "--")) << e;
}

TEST(RunScenario, ALongCapsuleNamesItsLength) {
  const std::string e =
      parse_error({{"geometry = \"sphere\" ", "geometry = \"cylinder\" "},
                   {"outer_radius_m = 0.03 ", "outer_radius_m = 0.03\nlength_m = 8.0 "}});
  EXPECT_TRUE(has(e, "key 'shell.length_m'")) << e;
  EXPECT_TRUE(has(e, "8 cm is 0.08")) << e;
}

TEST(RunScenario, AMicrometreShellIsTheSolversRuleNamingMetres) {
  const std::string e = parse_error({{"inner_radius_m = 0.02 ", "inner_radius_m = 0.0 "},
                                     {"outer_radius_m = 0.03 ", "outer_radius_m = 1e-6 "}});
  EXPECT_TRUE(has(e, "key 'shell.outer_radius_m'")) << e;
  EXPECT_TRUE(has(e, "(1e-06 m)")) << e;
}

TEST(RunScenario, AnEdgeThatAsksForTooManyTrianglesNamesTheMeshKey) {
  const std::string e = parse_error({{"edge_length_m = 2.5e-3 ", "edge_length_m = 1e-6 "}});
  EXPECT_TRUE(has(e, "key 'mesh.edge_length_m'")) << e;
  EXPECT_TRUE(has(e, "[mesh] triangles")) << e;
  EXPECT_FALSE(has(e, "--triangles")) << e;
}

TEST(RunScenario, ShippedScenariosAreFilmable) {
  EXPECT_EQ(parse_error({}), "");
  for (const auto& f : std::filesystem::directory_iterator(std::filesystem::path(THAW_SOURCE_DIR) /
                                                           "data/scenarios"))
    if (f.path().extension() == ".toml") {
      EXPECT_NO_THROW(read_run_scenario(f.path())) << f.path();
    }
}

}  // namespace
}  // namespace thaw::pipeline
