// The [caustics] and [camera] key tables (render/scene/caustic_keys.h, camera_keys.h) against
// what reads them: the parser reads every row's key (a required one must be there), the rules
// name the row's key, and docs/render.md's rows are the tables', row for row.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "base/error.h"
#include "render/format/scene_parser.h"
#include "render/scene/camera_keys.h"
#include "render/scene/caustic_keys.h"
#include "render/scene/environment_keys.h"
#include "render/scene/light_keys.h"
#include "render/scene/scene_rules.h"

namespace thaw::render {
namespace {

std::string docs_render_md() {
  std::ifstream in(std::string(THAW_SOURCE_DIR) + "/docs/render.md");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

const char* kCamera = R"([camera]
position = [0, 1, 5]
look_at = [0, 0, 0]
vertical_fov_deg = 40
)";

/// The problem (where: problem) parsing `text` reports, or "" if it parses.
std::string problem_of(const std::string& text) {
  try {
    parse_scene_string(text, "s.toml");
  } catch (const UserError& e) {
    return e.where() + ": " + e.problem();
  }
  return "";
}

template <class Row>
void expect_unique_names(std::span<const Row> rows) {
  std::set<std::string_view> names;
  for (const Row& r : rows) {
    EXPECT_TRUE(names.insert(r.name).second) << r.name;
    EXPECT_EQ(find_key(rows, r.name), &r);
  }
}

TEST(SectionKeys, NamesAreUniqueAndFound) {
  expect_unique_names(camera_keys());
  expect_unique_names(caustic_keys());
  expect_unique_names(light_keys());
  expect_unique_names(environment_keys());
}

TEST(SectionKeys, EnvironmentRowsOfAKindApplyToItAlone) {
  const SceneDescription s = parse_scene_string(
      std::string(kCamera) +
          "[environment]\nkind = \"sky\"\nzenith = [0, 0, 1]\nexponent = 2\nintensity = 3\n" +
          "haze_distance = 10\n",
      "s.toml");
  EXPECT_EQ(s.environment.kind, EnvironmentDescription::Kind::sky);
  EXPECT_EQ(s.environment.zenith, (RgbD{0, 0, 1}));
  EXPECT_EQ(s.environment.exponent, 2.0);
  EXPECT_EQ(s.environment.intensity, 3.0);
  EXPECT_EQ(s.environment.haze_distance, 10.0);
  EXPECT_NE(problem_of(std::string(kCamera) + "[environment]\nzenith = [0, 0, 1]\n").find("zenith"),
            std::string::npos);  // a constant environment has no sky colours
  EXPECT_NE(problem_of(std::string(kCamera) + "[environment]\nkind = \"latlong\"\n").find("file"),
            std::string::npos);  // a map needs its file
  EXPECT_NE(problem_of(std::string(kCamera) + "[environment]\nkind = \"dome\"\n")
                .find("unknown environment 'dome' (expected constant, sky or latlong)"),
            std::string::npos);
}

TEST(SectionKeys, LightRowsAreReadAndASpheresKeysApplyToItAlone) {
  const std::string light = "[[lights]]\nposition = [0, 5, 0]\n";
  const SceneDescription s = parse_scene_string(
      std::string(kCamera) + light + "kind = \"sphere\"\nradius = 0.5\nsamples = 8\n" +
          "color = [1, 0.5, 0]\nintensity = 2\nfalloff = \"inverse_square\"\n",
      "s.toml");
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].kind, LightDescription::Kind::sphere);
  EXPECT_EQ(s.lights[0].radius, 0.5);
  EXPECT_EQ(s.lights[0].samples, 8);
  EXPECT_EQ(s.lights[0].color, (RgbD{1, 0.5, 0}));
  EXPECT_EQ(s.lights[0].intensity, 2.0);
  EXPECT_EQ(s.lights[0].falloff, LightDescription::Falloff::inverse_square);
  EXPECT_NE(problem_of(std::string(kCamera) + light + "radius = 0.5\n").find("radius"),
            std::string::npos);  // a point light has no radius
  EXPECT_NE(problem_of(std::string(kCamera) + light + "kind = \"sphere\"\n").find("radius"),
            std::string::npos);  // a sphere light needs one
  EXPECT_NE(problem_of(std::string(kCamera) + light + "kind = \"spot\"\n")
                .find("unknown light kind 'spot' (expected point or sphere)"),
            std::string::npos);
  EXPECT_NE(problem_of(std::string(kCamera) + light + "intensity = -1\n")
                .find("must not be negative (got -1)"),
            std::string::npos);
}

TEST(SectionKeys, CameraRowsAreReadAndRequiredOnesMustBeThere) {
  const SceneDescription s =
      parse_scene_string(std::string(kCamera) + "up = [0, 0, 1]\nmedium = \"vacuum\"\n", "s.toml");
  EXPECT_EQ(s.camera.position, (Vec3d{0, 1, 5}));
  EXPECT_EQ(s.camera.up, (Vec3d{0, 0, 1}));
  EXPECT_EQ(s.camera.vertical_fov_deg, 40.0);
  EXPECT_EQ(s.camera.medium, "vacuum");
  for (const CameraKey& row : camera_keys()) {
    if (row.default_text != "required") continue;
    std::string text = kCamera;
    const std::string line = std::string(row.name) + " = ";
    const auto at = text.find(line);
    ASSERT_NE(at, std::string::npos) << row.name;
    text.erase(at, text.find('\n', at) + 1 - at);
    EXPECT_NE(problem_of(text).find("camera." + std::string(row.name)), std::string::npos)
        << row.name << ": " << problem_of(text);
  }
  EXPECT_NE(problem_of(std::string(kCamera) + "up = [0, 2, 0]\n").find("unit vector"),
            std::string::npos);
}

TEST(SectionKeys, CausticRulesNameTheRowsKeyAndAutomaticPasses) {
  EXPECT_EQ(find_scene_problem(SceneDescription{}), std::nullopt);
  for (const CausticKey& row : caustic_keys()) {
    if (std::holds_alternative<FlagKey<CausticSettings>>(row.value)) continue;
    SceneDescription bad;
    if (const auto* k = std::get_if<OptionalIntegerKey<CausticSettings>>(&row.value))
      bad.caustics.*(k->field) = -5;
    if (const auto* k = std::get_if<OptionalNumberKey<CausticSettings>>(&row.value))
      bad.caustics.*(k->field) = -5.0;
    const auto found = find_scene_problem(bad);
    ASSERT_TRUE(found.has_value()) << row.name;
    EXPECT_EQ(found->key, "caustics." + std::string(row.name));
    EXPECT_NE(problem_of(std::string(kCamera) + "[caustics]\n" + std::string(row.name) + " = -5\n")
                  .find("caustics." + std::string(row.name)),
              std::string::npos)
        << row.name;
  }
}

TEST(SectionKeys, DocsRenderMdListsExactlyTheTablesRows) {
  const std::string docs = docs_render_md();
  ASSERT_FALSE(docs.empty()) << "docs/render.md";
  for (const auto& [expected, table] :
       {std::pair{key_docs_rows(caustic_keys(), "[caustics] "), "caustic_keys.cpp"},
        std::pair{key_docs_rows(camera_keys(), "[camera] "), "camera_keys.cpp"},
        std::pair{key_docs_rows(light_keys(), "[[lights]] "), "light_keys.cpp"},
        std::pair{key_docs_rows(environment_keys(), "[environment] "), "environment_keys.cpp"}})
    EXPECT_NE(docs.find(expected), std::string::npos)
        << "docs/render.md's rows differ from render/scene/" << table << "; they should read:\n"
        << expected;
}

}  // namespace
}  // namespace thaw::render
