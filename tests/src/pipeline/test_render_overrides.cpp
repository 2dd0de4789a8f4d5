// Tests of src/pipeline/render_overrides: `thaw run --size WxH --spp N` parsing, limits, and the
// render fingerprint (and only it) changing.
#include "src/pipeline/render_overrides.h"

#include <gtest/gtest.h>

#include "base/error.h"
#include "render/format/scene_parser.h"

namespace thaw::pipeline {
namespace {

TEST(RenderOverrides, ParsesSizes) {
  const RenderOverrides o = parse_size_override("640x480");
  EXPECT_EQ(*o.width, 640);
  EXPECT_EQ(*o.height, 480);
  EXPECT_EQ(*parse_size_override("1X2").height, 2);
  EXPECT_EQ(*parse_size_override("16384x4096").width, render::kMaxImageSide);
}

TEST(RenderOverrides, RejectsBadSizesNamingTheOption) {
  for (const char* bad : {"640", "x480", "640x", "640x480x2", "a x b", "640 x 480", "0x480",
                          "640x0", "-640x480", "16385x1", "16384x16384", "1e3x480", ""}) {
    try {
      parse_size_override(bad);
      ADD_FAILURE() << "accepted \"" << bad << "\"";
    } catch (const UserError& e) {
      EXPECT_EQ(e.where(), "--size") << bad;
    }
  }
}

TEST(RenderOverrides, SppRange) {
  EXPECT_EQ(checked_spp_override(1), 1);
  EXPECT_EQ(checked_spp_override(65536), 65536);
  EXPECT_THROW(checked_spp_override(0), UserError);
  EXPECT_THROW(checked_spp_override(-4), UserError);
  EXPECT_THROW(checked_spp_override(65537), UserError);
}

/// The problem a scene file reports for `image_keys` in its [image] table.
std::string file_problem(const std::string& image_keys) {
  try {
    render::parse_scene_string("[image]\n" + image_keys +
                                   "\n[camera]\nposition = [0.0, 0.0, 5.0]\n"
                                   "look_at = [0.0, 0.0, 0.0]\nvertical_fov_deg = 40.0\n",
                               "s.toml");
  } catch (const UserError& e) {
    return e.problem();
  }
  return "";
}

template <typename F>
std::string flag_problem(F f) {
  try {
    f();
  } catch (const UserError& e) {
    return e.problem();
  }
  return "";
}

// --size and --spp are checked by the file keys' rules: the same words for the same value.
TEST(RenderOverrides, SameMessageAsTheFileKey) {
  EXPECT_EQ(flag_problem([] { checked_spp_override(0); }), file_problem("samples_per_pixel = 0"));
  EXPECT_EQ(flag_problem([] { checked_spp_override(70000); }),
            file_problem("samples_per_pixel = 70000"));
  EXPECT_EQ(flag_problem([] { parse_size_override("0x480"); }), file_problem("width = 0"));
  EXPECT_EQ(flag_problem([] { parse_size_override("16384x16384"); }),
            file_problem("width = 16384\nheight = 16384"));
  EXPECT_NE(file_problem("width = 0"), "");
}

TEST(RenderOverrides, ChangeTheImageAndOnlyTheRenderFingerprint) {
  RunScenario sc = default_run_scenario();
  const RunScenario before = sc;
  RenderOverrides o = parse_size_override("64x48");
  o.samples_per_pixel = 3;
  apply_render_overrides(sc, o);
  EXPECT_EQ(sc.scene.image.width, 64);
  EXPECT_EQ(sc.scene.image.height, 48);
  EXPECT_EQ(sc.scene.image.samples_per_pixel, 3);
  EXPECT_NE(sc.render_text, before.render_text);
  EXPECT_EQ(sc.simulation_text, before.simulation_text);
  EXPECT_EQ(sc.mesh_text, before.mesh_text);
  EXPECT_EQ(sc.film_text, before.film_text);
  // No override: nothing changes.
  RunScenario same = before;
  apply_render_overrides(same, {});
  EXPECT_EQ(same.render_text, before.render_text);
}

}  // namespace
}  // namespace thaw::pipeline
