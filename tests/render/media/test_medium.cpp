// Parsing [media.NAME] tables into MediumSpec and building Media: presets, explicit models,
// absorption overrides, and every bad input named by the issue (unknown preset, table out of
// range, Sellmeier pole inside 380-780 nm, negative absorption) as a UserError naming the key.
#include <gtest/gtest.h>

#include <string>

#include "base/error.h"
#include "base/format/toml_table.h"
#include "render/format/medium_library.h"
#include "render/format/medium_parser.h"
#include "render/media/medium.h"

namespace thaw::render::media {
namespace {

Medium build(const std::string& toml, const std::string& name = "m") {
  const TomlTable root = TomlTable::parse_string(toml, "scene.toml");
  const MediumSpec spec = parse_medium_spec(root.table("media").table(name), name);
  root.check_no_unknown_keys();
  return build_medium(resolve_preset(spec));
}

std::string error_of(const std::string& toml) {
  try {
    build(toml);
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

TEST(Medium, PresetWithScaledAbsorption) {
  const Medium m = build("[media.m]\npreset = \"water-0c\"\nabsorption_scale = 10.0\n");
  EXPECT_TRUE(m.is_dispersive());
  EXPECT_NEAR(m.n_at(589.3), find_medium_preset("water-0c")->ior->n_at(589.3), 1e-15);
  EXPECT_NEAR(m.absorption_per_m_at(700.0), 6.24, 1e-9);
}

TEST(Medium, ExplicitModels) {
  EXPECT_FALSE(build("[media.m]\nior = 1.31\n").is_dispersive());
  EXPECT_NEAR(build("[media.m]\nsellmeier = { B = [1.03961212, 0.231792344, 1.01046945], "
                    "C = [0.00600069867, 0.0200179144, 103.560653] }\n")
                  .n_at(587.56),
              1.5168, 5e-5);
  EXPECT_NEAR(build("[media.m]\ncauchy = { A = 1.3, B = 0.004 }\n").n_at(400.0), 1.3 + 0.004 / 0.16,
              1e-12);
  EXPECT_NEAR(
      build("[media.m]\ntable = { wavelength_nm = [380, 780], n = [1.4, 1.3] }\n").n_at(580.0),
      1.35, 1e-12);
  const Medium a = build("[media.m]\nior = 1.5\nabsorption_per_m = 2.0\n");
  EXPECT_DOUBLE_EQ(a.absorption_per_m_at(500.0), 2.0);
  const Medium t = build(
      "[media.m]\nior = 1.5\nabsorption_per_m = { wavelength_nm = [300, 800], per_m = [0.0, 5.0] "
      "}\n");
  EXPECT_DOUBLE_EQ(t.absorption_per_m_at(550.0), 2.5);
  EXPECT_FALSE(build("[media.m]\npreset = \"n-bk7\"\n").absorbs());
}

TEST(Medium, UnknownPresetIsAnErrorListingTheKnownOnes) {
  const std::string e = error_of("[media.m]\npreset = \"water-4c\"\n");
  EXPECT_NE(e.find("scene.toml"), std::string::npos) << e;
  EXPECT_NE(e.find("media.m.preset"), std::string::npos) << e;
  EXPECT_NE(e.find("water-4c"), std::string::npos) << e;
  EXPECT_NE(e.find("water-0c"), std::string::npos) << e;
}

TEST(Medium, TableOutOfRangeIsAnError) {
  const std::string e =
      error_of("[media.m]\ntable = { wavelength_nm = [400, 700], n = [1.4, 1.3] }\n");
  EXPECT_NE(e.find("media.m.table.wavelength_nm"), std::string::npos) << e;
  EXPECT_NE(e.find("380-780"), std::string::npos) << e;
}

TEST(Medium, SellmeierPoleIsAnError) {
  // A classic mistake: C in nm^2 (or the pole wavelength itself) instead of um^2.
  const std::string e = error_of("[media.m]\nsellmeier = { B = [1.0], C = [0.2] }\n");
  EXPECT_NE(e.find("media.m.sellmeier.C[0]"), std::string::npos) << e;
  EXPECT_NE(e.find("pole"), std::string::npos) << e;
}

TEST(Medium, NegativeAbsorptionIsAnError) {
  const std::string e = error_of("[media.m]\nior = 1.3\nabsorption_per_m = -1.0\n");
  EXPECT_NE(e.find("media.m.absorption_per_m"), std::string::npos) << e;
  EXPECT_NE(error_of("[media.m]\nior = 1.3\nabsorption_scale = -2.0\n").find("absorption_scale"),
            std::string::npos);
}

TEST(Medium, AmbiguousOrMissingIndexIsAnError) {
  EXPECT_NE(error_of("[media.m]\nior = 1.3\npreset = \"vacuum\"\n").find("exactly one"),
            std::string::npos);
  EXPECT_NE(error_of("[media.m]\nabsorption_per_m = 1.0\n").find("index of refraction"),
            std::string::npos);
  EXPECT_NE(
      error_of("[media.m]\nsellmeier = { B = [1.0], C = [0.01], form = \"n\" }\n").find("form"),
      std::string::npos);
}

TEST(Medium, UnknownKeysAreErrors) {
  EXPECT_NE(error_of("[media.m]\nior = 1.3\nabsorbtion_scale = 2.0\n").find("absorbtion_scale"),
            std::string::npos);
  EXPECT_NE(
      error_of("[media.m]\nsellmeier = { B = [1.0], C = [0.01], D = [1.0] }\n").find("sellmeier.D"),
      std::string::npos);
}

TEST(MediumLibrary, HasTheIssuePresetsWithSources) {
  for (const char* name : {"vacuum", "air", "water-20c", "water-0c", "ice-ih", "n-bk7", "n-sf10",
                           "fused-silica", "diamond"}) {
    const MediumSpec* p = find_medium_preset(name);
    ASSERT_NE(p, nullptr) << name;
    EXPECT_FALSE(p->source.empty()) << name;
    EXPECT_NO_THROW(build_medium(*p)) << name;
  }
  EXPECT_EQ(find_medium_preset("unobtainium"), nullptr);
}

}  // namespace
}  // namespace thaw::render::media
