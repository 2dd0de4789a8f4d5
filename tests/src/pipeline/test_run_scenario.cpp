// Tests src/pipeline/run_scenario.h: [film] frames_format (issue 13): "png" by default, "exr"
// accepted, anything else a UserError naming the file and the key.
#include "src/pipeline/run_scenario.h"

#include <gtest/gtest.h>

#include <string>

#include "src/common/error.h"
#include "src/common/toml_table.h"

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

}  // namespace
}  // namespace thaw::pipeline
