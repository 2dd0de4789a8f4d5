// Tests src/pipeline/run_scenario.h: [film] frames_format (issue 13): "png" by default, "exr"
// accepted, anything else a UserError naming the file and the key; [render.shell] placement
// (issue 12): a floor or centre too far out for single precision names its key.
#include "src/pipeline/run_scenario.h"

#include <gtest/gtest.h>

#include <string>

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
