// Tests render/scene/scene_rules.h: each limit at its bounds, the same words from the scene file
// and from a scene built in code, and the placement rule that stops huge translations before
// they collapse a mesh (the class of `[render.shell] floor_y = 2147483647`).
#include "render/scene/scene_rules.h"

#include <gtest/gtest.h>

#include <cmath>

#include "base/error.h"
#include "render/format/scene_parser.h"
#include "render/scene/scene.h"
#include "tests/render/test_util.h"

namespace thaw::render {
namespace {

TEST(SceneRules, IntegerLimitsAcceptTheirBoundsAndRejectOneBeyond) {
  struct Case {
    std::optional<std::string> (*rule)(long long);
    long long lo, hi;
  };
  const Case cases[] = {
      {image_side_problem, 1, kMaxImageSide},
      {samples_per_pixel_problem, 1, kMaxSamplesPerPixel},
      {min_samples_problem, 2, kMaxSamplesPerPixel},
      {max_depth_problem, 1, kMaxDepth},
      {dispersion_wavelengths_problem, kMinDispersionWavelengths, kMaxDispersionWavelengths},
      {light_samples_problem, 1, kMaxLightSamples},
      {caustic_photons_problem, kMinCausticPhotons, kMaxCausticPhotons}};
  for (const Case& c : cases) {
    EXPECT_FALSE(c.rule(c.lo));
    EXPECT_FALSE(c.rule(c.hi));
    ASSERT_TRUE(c.rule(c.lo - 1));
    EXPECT_NE(c.rule(c.lo - 1)->find("(got " + std::to_string(c.lo - 1) + ")"), std::string::npos)
        << *c.rule(c.lo - 1);
    EXPECT_TRUE(c.rule(c.hi + 1));
  }
  // 64-bit values are judged whole (a file's 2^32 + 1 must not wrap to 1).
  EXPECT_TRUE(image_side_problem((1LL << 32) + 1));
}

TEST(SceneRules, RealLimitsRejectNaNAndOutOfRange) {
  EXPECT_FALSE(vertical_fov_problem(179.9));
  EXPECT_TRUE(vertical_fov_problem(180.0));
  EXPECT_TRUE(vertical_fov_problem(0.0));
  EXPECT_TRUE(vertical_fov_problem(std::nan("")));
  EXPECT_FALSE(ior_problem(1.0));
  EXPECT_TRUE(ior_problem(kMaxIor));
  EXPECT_TRUE(ior_problem(0.999));
  EXPECT_FALSE(dispersion_resolution_problem(kMinDispersionResolutionNm));
  EXPECT_TRUE(dispersion_resolution_problem(0.0));
  EXPECT_TRUE(light_radius_problem(1e39));  // finite in double, infinite in float
  EXPECT_EQ(*adaptive_threshold_problem(0.0), "must be between 0.0001 and 1 display units (got 0)");
  EXPECT_TRUE(image_pixels_problem(kMaxImageSide, kMaxImageSide));
  // Found by the bad-input sweep (tests/src/cli/bad_input_sweep.sh): each of these was accepted.
  EXPECT_TRUE(vertical_fov_problem(1e-300));  // the pixel footprint underflowed
  EXPECT_FALSE(vertical_fov_problem(kMinFovDeg));
  EXPECT_EQ(*exposure_problem(std::nan("")), "must be between -64 and 64 stops (got nan)");
  EXPECT_TRUE(exposure_problem(1e308));  // 2^exposure was infinite: NaN pixels
  EXPECT_FALSE(exposure_problem(-kMaxExposureStops));
  EXPECT_TRUE(caustic_radius_problem(1e-300));  // 0 in single precision: an internal check failed
  EXPECT_FALSE(caustic_radius_problem(kMinCausticRadius));
  EXPECT_TRUE(caustic_photons_problem(kMaxCausticPhotons + 1));
  EXPECT_FALSE(image_pixels_problem(kMaxImageSide, kMaxImagePixels / kMaxImageSide));
}

TEST(SceneRules, PlacementKeepsDetailToASixtyFourthOfItself) {
  // Floats in [2^17, 2^18) are 2^-6 apart: 64 steps make 1, so detail 1 passes up to 2^18 and
  // fails from 2^18 on, where the spacing doubles.
  EXPECT_FALSE(placement_problem(262143.0, 1.0));
  EXPECT_TRUE(placement_problem(262144.0, 1.0));
  EXPECT_TRUE(placement_problem(1e39, 1e30));  // beyond float altogether
  // The example of the issue: a 2.5 mm mesh edge (a 3 cm shell) at y = 2^31 - 1.
  const auto p = placement_problem(2147483647.0, 0.0025);
  ASSERT_TRUE(p);
  EXPECT_NE(p->find("single precision"), std::string::npos) << *p;
  EXPECT_NE(p->find("steps of 256"), std::string::npos) << *p;
  EXPECT_FALSE(placement_problem(100.0, 0.0025));  // a shell on a floor 100 m up is fine
}

/// The problem build_scene reports for `desc`, or "" if it builds.
std::string build_problem(const SceneDescription& desc) {
  try {
    build_scene(desc);
  } catch (const UserError& e) {
    return e.where() + ": " + e.problem();
  }
  return "";
}

/// The problem the parser reports for `text`, keyed as build_scene keys it.
std::string parse_problem(const std::string& text) {
  try {
    parse_scene_string(text, "rules.toml");
  } catch (const UserError& e) {
    // "line N, key 'image.width'" -> "image.width"
    const auto q = e.where().find('\'');
    return e.where().substr(q + 1, e.where().size() - q - 2) + ": " + e.problem();
  }
  return "";
}

// The same bad value says the same thing from a file and from a scene built in code.
TEST(SceneRules, FileAndCodeGiveTheSameMessage) {
  const std::string camera =
      "[camera]\nposition = [0.0, 0.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\nvertical_fov_deg = ";
  struct Case {
    std::string file;
    void (*edit)(SceneDescription&);
  };
  const Case cases[] = {
      {"[image]\nwidth = 0\n" + camera + "40.0\n", [](SceneDescription& d) { d.image.width = 0; }},
      {"[image]\nsamples_per_pixel = 70000\n" + camera + "40.0\n",
       [](SceneDescription& d) { d.image.samples_per_pixel = 70000; }},
      {"[image]\nmax_depth = 257\n" + camera + "40.0\n",
       [](SceneDescription& d) { d.image.max_depth = 257; }},
      {"[image]\ndispersion_resolution_nm = 200.0\n" + camera + "40.0\n",
       [](SceneDescription& d) { d.image.dispersion_resolution_nm = 200.0; }},
      {camera + "180.0\n", [](SceneDescription& d) { d.camera.vertical_fov_deg = 180.0; }},
      {camera + "40.0\n[media.glass]\nior = 12.0\n",
       [](SceneDescription& d) { d.media.push_back(test::medium("glass", 12.0)); }},
      {camera + "40.0\n[caustics]\nphotons = 0\n",
       [](SceneDescription& d) { d.caustics.photons = 0; }},
  };
  for (const Case& c : cases) {
    SceneDescription d;
    c.edit(d);
    const std::string from_file = parse_problem(c.file);
    EXPECT_FALSE(from_file.empty()) << c.file;
    EXPECT_EQ(from_file, build_problem(d)) << c.file;
  }
}

// A mesh moved far from the origin is named for its placement, not for what the collapse breaks
// later (before: "a dielectric mesh must be oriented outward").
TEST(SceneRules, HugeTranslationIsAPlacementErrorAtTheTranslate) {
  SceneDescription d;
  d.media = {test::medium("ice", 1.31)};
  auto& o = d.add_dielectric_mesh(std::make_shared<TriangleMesh>(test::icosphere(2, 0.03f)), "ice",
                                  "vacuum", "shell outer surface");
  o.translate = {0.0, 2147483647.0, 0.0};
  const std::string problem = build_problem(d);
  EXPECT_NE(problem.find("shell outer surface.translate: reaches"), std::string::npos) << problem;
  EXPECT_EQ(problem.find("oriented outward"), std::string::npos) << problem;
  o.translate = {0.0, 100.0, 0.0};
  EXPECT_EQ(build_problem(d), "");
}

TEST(SceneRules, FarSmallSphereIsAPlacementErrorAtTheCentre) {
  SceneDescription d;
  d.media = {test::medium("ice", 1.31)};
  ObjectDescription ball;
  ball.label = "ball";
  ball.center = {1e9, 0.0, 0.0};
  ball.radius = 0.01;
  ball.inside = "ice";
  ball.outside = "vacuum";
  d.objects.push_back(ball);
  EXPECT_NE(build_problem(d).find("ball.center: reaches"), std::string::npos) << build_problem(d);
}

// Found by the bad-input sweep: a camera at 1e308 (finite) overflowed the viewing direction's
// length and was reported as "up must not be parallel"; a sphere of radius 1e-300 or 1e308 was
// reported against its centre. Each names its own key now.
TEST(SceneRules, HugeCameraAndSphereSizesNameTheirKey) {
  CameraDescription cam;
  cam.position = {1e308, 0.0, 0.0};
  cam.look_at = {0.0, 0.0, 0.0};
  cam.vertical_fov_deg = 40.0;
  ASSERT_TRUE(camera_problem(cam));
  EXPECT_EQ(camera_problem(cam)->key, "position");
  cam.position = {0.0, 0.0, 5.0};
  cam.look_at = {0.0, -1e20, 0.0};
  ASSERT_TRUE(camera_problem(cam));
  EXPECT_EQ(camera_problem(cam)->key, "look_at");
  cam.look_at = {0.0, 0.0, kMaxCoordinate};
  EXPECT_FALSE(camera_problem(cam));
  ObjectDescription ball;
  ball.shape = ObjectDescription::Shape::sphere;
  ball.center = {0.0, 0.0, 0.0};
  for (double r : {1e-300, 1e308, 0.0, -1.0}) {
    ball.radius = r;
    ASSERT_TRUE(object_problem(ball)) << r;
    EXPECT_EQ(object_problem(ball)->key, "radius") << r;
  }
  ball.radius = 1.0;
  EXPECT_FALSE(object_problem(ball));
}

}  // namespace
}  // namespace thaw::render
