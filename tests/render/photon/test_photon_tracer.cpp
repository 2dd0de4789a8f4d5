// One photon's path through dielectrics against geometric optics: the ball lens's paraxial
// focus, slab transmission with multiple reflections, total internal reflection, Beer-Lambert,
// dispersion and index-matched interfaces.
#include "render/photon/photon_tracer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/render/photon/photon_test_scenes.h"

namespace thaw::render::photon {
namespace {

using test::scene_from;

double sum_weights(const PathEvents& ev, PathEnd end) {
  double s = 0;
  for (const auto& e : ev)
    if (e.end == end) s += e.weight;
  return s;
}

double total_weight(const PathEvents& ev) {
  double s = 0;
  for (const auto& e : ev) s += e.weight;
  return s;
}

/// The escaped event carrying the most weight (the twice-refracted ray through a lens).
const PathEvent& main_escape(const PathEvents& ev) {
  const PathEvent* best = nullptr;
  for (const auto& e : ev)
    if (e.end == PathEnd::escaped && (!best || e.weight > best->weight)) best = &e;
  EXPECT_NE(best, nullptr);
  return *best;
}

/// Where the ray (origin, direction) crosses the y axis' plane x = 0 (a meridional ray in the
/// x-y plane): its y coordinate.
double axis_crossing_y(const Vec3& o, const Vec3& d) {
  return double(o.y) - double(o.x) * double(d.y) / double(d.x);
}

// Ball lens (Hecht, Optics, 5th ed., sec. 6.2 / any optics text): the paraxial focal length from
// the centre is f = n R / (2 (n - 1)) (2.113 R for ice, n = 1.31), and an object at distance s
// from the centre images at s' with 1/s' = 1/f - 1/s (principal planes at the centre). Rays at
// height h = 0.005 R: spherical aberration shifts their crossing by O(h^2 / R) ~ 2.5e-5 R x a
// coefficient of order 1-10, float directions add ~1e-7 / (h / f) ~ 4e-5 relative: 1e-3 R holds.
/// A ball of radius 1 and index `n` at the origin in vacuum, nothing else.
Scene lone_ball(const std::string& medium_keys, const std::string& image = "") {
  return scene_from("[image]\n" + image + R"(
[[lights]]
position = [0.0, 30.0, 0.0]
[media.glass]
)" + medium_keys + R"(
[[objects]]
shape = "sphere"
center = [0.0, 0.0, 0.0]
radius = 1.0
inside = "glass"
outside = "vacuum"
)" + test::kCamera);
}

TEST(PhotonTracer, BallLensParaxialFocus) {
  for (const double n : {1.31, 1.5}) {
    const Scene scene = lone_ball("ior = " + std::to_string(n));
    const PhotonTracer tracer(scene);
    PathEvents ev;
    const double f = n / (2 * (n - 1));
    // Parallel light (a source at infinity) coming down the y axis.
    tracer.trace(Ray{{0.005f, 10.0f, 0.0f}, {0, -1, 0}}, 0, 589.0, ev);
    EXPECT_NEAR(total_weight(ev), 1.0, 1e-6);
    const PathEvent& out = main_escape(ev);
    EXPECT_NEAR(-axis_crossing_y(out.position, out.normal), f, 1e-3) << "n = " << n;
    // A point source at s = 6 R: image at s' = 1 / (1/f - 1/s).
    const double s = 6.0, s_image = 1.0 / (1.0 / f - 1.0 / s);
    const Vec3 d = normalize(Vec3{0.005f, float(-s), 0.0f});
    tracer.trace(Ray{{0.0f, float(s), 0.0f}, d}, 0, 589.0, ev);
    const PathEvent& out2 = main_escape(ev);
    EXPECT_NEAR(-axis_crossing_y(out2.position, out2.normal), s_image, 2e-3 * s_image)
        << "n = " << n;
  }
}

// A slab at normal incidence transmits (1 - R)^2 on the direct pass, R = ((n-1)/(n+1))^2
// (0.9643 for n = 1.31); with every internal reflection followed the sum is (1 - R)^2 sum R^2k
// = (1 - R) / (1 + R) (0.9646). With min_weight = 1/255 the second pass (R^2 = 3.2e-4) is cut.
// Float rounding of the weights: 1e-6.
TEST(PhotonTracer, SlabAtNormalIncidence) {
  const double n = 1.31, r = std::pow((n - 1) / (n + 1), 2);
  for (const bool all_orders : {false, true}) {
    const Scene scene = scene_from(std::string("[image]\n") +
                                   (all_orders ? "min_weight = 0.0\nmax_depth = 64\n" : "") +
                                   R"(
[[lights]]
position = [0.0, 10.0, 0.0]
[media.ice]
ior = 1.31
[materials.white]
kind = "matte"
[[objects]]
shape = "box"
min = [-5.0, 0.0, -5.0]
max = [5.0, 0.1, 5.0]
inside = "ice"
outside = "vacuum"
[[objects]]
shape = "plane"
point = [0.0, -1.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "white"
)" + test::kCamera);
    const PhotonTracer tracer(scene);
    PathEvents ev;
    tracer.trace(Ray{{0.1f, 5.0f, 0.2f}, {0, -1, 0}}, 0, 589.0, ev);
    const double expected = all_orders ? (1 - r) / (1 + r) : (1 - r) * (1 - r);
    EXPECT_NEAR(sum_weights(ev, PathEnd::stored), expected, 1e-6);
    EXPECT_NEAR(total_weight(ev), 1.0, 1e-6);
    EXPECT_NEAR(sum_weights(ev, PathEnd::stored) / (1 - r) / (1 - r),
                all_orders ? 1 / (1 - r * r) : 1.0, 1e-6);
  }
}

// Inside a glass cube (n = 1.5, critical angle 41.8 deg) a photon along a diagonal meets every
// face at 54.7 deg and is totally reflected: nothing leaves, all of it is cut at max_depth.
TEST(PhotonTracer, TotalInternalReflection) {
  const Scene scene = scene_from(R"(
[image]
max_depth = 12
[media.glass]
ior = 1.5
[[objects]]
shape = "box"
min = [-1.0, -1.0, -1.0]
max = [1.0, 1.0, 1.0]
inside = "glass"
outside = "vacuum"
)" + test::kCamera);
  const PhotonTracer tracer(scene);
  PathEvents ev;
  tracer.trace(Ray{{0.1f, -0.3f, 0.2f}, normalize(Vec3{1, 1, 1})}, 1, 589.0,
               ev);  // medium 1 = glass
  EXPECT_EQ(sum_weights(ev, PathEnd::escaped), 0.0);
  EXPECT_NEAR(sum_weights(ev, PathEnd::cut), 1.0, 1e-6);
  EXPECT_EQ(tracer.medium_at({0, 0, 0}), 1u);
  EXPECT_EQ(tracer.medium_at({3, 0, 0}), 0u);
}

/// A 0.5 m slab of medium `medium_keys` (n and absorption) over a matte floor (spectral unless
/// `spectral` is false).
Scene absorbing_slab(const std::string& medium_keys, bool spectral = true) {
  return scene_from(std::string("[image]\nspectral = ") + (spectral ? "true" : "false") + R"(
[[lights]]
position = [0.0, 10.0, 0.0]
[media.tinted]
)" + medium_keys + R"(
[materials.white]
kind = "matte"
[[objects]]
shape = "box"
min = [-5.0, 0.0, -5.0]
max = [5.0, 0.5, 5.0]
inside = "tinted"
outside = "vacuum"
[[objects]]
shape = "plane"
point = [0.0, -1.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "white"
)" + test::kCamera);
}

// Beer-Lambert: an index-matched slab (n = 1) absorbing alpha = 0.5/m at 380 nm rising to 3/m at
// 780 nm passes exp(-alpha(lambda) 0.5 m) at normal incidence; the rest is absorbed. It absorbs,
// so it is not invisible (its shadow rays are blocked) and what passes is stored as a caustic.
// Float exp and distance: 1e-6.
TEST(PhotonTracer, BeerLambertPerWavelength) {
  const Scene scene = absorbing_slab(
      "ior = 1.0\nabsorption_per_m = { wavelength_nm = [380.0, 780.0], per_m = [0.5, 3.0] }");
  EXPECT_FALSE(scene.objects()[0].index_matched);
  const PhotonTracer tracer(scene);
  PathEvents ev;
  for (const double lambda : {420.0, 550.0, 700.0}) {
    tracer.trace(Ray{{0, 5, 0}, {0, -1, 0}}, 0, lambda, ev);
    const double alpha = 0.5 + 2.5 * (lambda - 380) / 400;
    EXPECT_NEAR(sum_weights(ev, PathEnd::stored), std::exp(-alpha * 0.5), 1e-6) << lambda;
    EXPECT_NEAR(sum_weights(ev, PathEnd::absorbed), 1 - std::exp(-alpha * 0.5), 1e-6) << lambda;
  }
}

// RGB scenes: photons keep the light's colour and carry the per-channel transmittance
// exp(-alpha_c 0.5 m) as their events' tint (alpha_c = Absorption::srgb_per_m, as the camera
// rays); the absorbed events carry the rest, so every channel's power is conserved. An absorbing
// slab is not index matched in RGB either. Float exp: 1e-6.
TEST(PhotonTracer, BeerLambertPerChannelInRgb) {
  const Scene scene = absorbing_slab(
      "ior = 1.0\nabsorption_per_m = { wavelength_nm = [380.0, 780.0], per_m = [0.5, 3.0] }",
      false);
  EXPECT_FALSE(scene.spectral());
  EXPECT_FALSE(scene.objects()[0].index_matched);
  const LinearSrgb a = scene.media()[1].optics.absorption().srgb_per_m();
  const PhotonTracer tracer(scene);
  PathEvents ev;
  tracer.trace(Ray{{0, 5, 0}, {0, -1, 0}}, 0, 550.0, ev);
  Rgb stored, absorbed;
  for (const auto& e : ev) {
    if (e.end == PathEnd::stored) stored += e.tint * e.weight;
    if (e.end == PathEnd::absorbed) absorbed += e.tint * e.weight;
  }
  EXPECT_NEAR(stored.r, std::exp(-a.r * 0.5), 1e-6);
  EXPECT_NEAR(stored.g, std::exp(-a.g * 0.5), 1e-6);
  EXPECT_NEAR(stored.b, std::exp(-a.b * 0.5), 1e-6);
  EXPECT_NEAR(stored.r + absorbed.r, 1.0, 1e-6);
  EXPECT_NEAR(stored.b + absorbed.b, 1.0, 1e-6);
  EXPECT_LT(stored.r, stored.b);  // alpha rises towards the red
}

// An index-matched, non-absorbing slab changes nothing: photons through it are direct light.
TEST(PhotonTracer, IndexMatchedInterfaceIsDirectLight) {
  const Scene scene = absorbing_slab("ior = 1.0");
  EXPECT_TRUE(scene.objects()[0].index_matched);
  const PhotonTracer tracer(scene);
  PathEvents ev;
  tracer.trace(Ray{{0.3f, 5, 0.1f}, {0, -1, 0}}, 0, 550.0, ev);
  EXPECT_EQ(sum_weights(ev, PathEnd::stored), 0.0);
  EXPECT_NEAR(sum_weights(ev, PathEnd::direct), 1.0, 1e-7);
}

// Dispersion: with N-SF10 (Sellmeier, n_F - n_C ~ 0.02) each wavelength focuses at its own
// f(lambda) = n(lambda) R / (2 (n(lambda) - 1)); blue (n larger) closer than red. Tolerance as in
// the ball-lens test.
TEST(PhotonTracer, DispersionFocusesEachWavelengthAtItsOwnDistance) {
  const Scene scene = lone_ball("preset = \"n-sf10\"", "spectral = true");
  const PhotonTracer tracer(scene);
  PathEvents ev;
  double previous = 0;
  for (const double lambda : {450.0, 550.0, 650.0}) {
    const double n = scene.media()[1].optics.n_at(lambda);
    EXPECT_NEAR(tracer.ior(1, lambda), n, 1e-5);  // the 1 nm table
    tracer.trace(Ray{{0.005f, 10.0f, 0.0f}, {0, -1, 0}}, 0, lambda, ev);
    const PathEvent& out = main_escape(ev);
    const double focus = -axis_crossing_y(out.position, out.normal);
    EXPECT_NEAR(focus, n / (2 * (n - 1)), 1e-3) << lambda;
    EXPECT_GT(focus, previous);
    previous = focus;
  }
}

}  // namespace
}  // namespace thaw::render::photon
