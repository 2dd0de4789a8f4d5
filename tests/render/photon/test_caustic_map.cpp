// The photon pass: flux conservation, units (same as direct light), the caustic's position,
// index-matched objects, white light, determinism across thread counts, settings.
#include "render/photon/caustic_map.h"

#include <gtest/gtest.h>

#include <cmath>

#include "render/accel/ray_record.h"
#include "render/photon/low_discrepancy.h"
#include "render/photon/photon_tracer.h"
#include "tests/render/photon/photon_test_scenes.h"

namespace thaw::render::photon {
namespace {

using test::ball_over_floor;
using test::scene_from;

double sum(const Flux& f) {
  return f.r + f.g + f.b;
}

// Flux conservation without absorption: everything sent into the ball's cone ends on the floor,
// in the sky, below min_weight or in the roulette's ledger (+w lost, -(T - w) gained), and the
// cone's power is I Omega = I 2 pi (1 - sqrt(1 - (R/D)^2)) per colour channel. The ledger holds
// to the float rounding of ~1e5 photon weights (1e-5); the cone's power is the sum of I Omega / N
// over the N photons sent, exact up to float (1e-5, the widened bounding sphere included). The
// roulette's net is zero on average with the variance accumulated over its decisions: within 4
// standard deviations (Halton decisions are stratified, so it is usually much closer). So what
// reached the floor plus what escaped equals what entered the cone to that sampling error.
TEST(CausticMap, FluxConservation) {
  const Scene scene =
      ball_over_floor("ior = 1.31", -1.0, "[0.0, 6.0, 0.0]", "", "photons = 100000");
  const CausticMap map = CausticMap::build(scene, 2);
  const CausticStatistics& st = map.statistics();
  const double intensity = 100.0, omega = 2 * M_PI * (1 - std::sqrt(1 - 1.0 / 36.0));
  EXPECT_EQ(st.photons_traced, 100000);
  EXPECT_NEAR(st.emitted.r, intensity * omega, 1e-5 * intensity * omega);
  EXPECT_NEAR(st.emitted.g, intensity * omega, 1e-5 * intensity * omega);
  const double ends = sum(st.stored) + sum(st.escaped) + sum(st.direct) + sum(st.cut) +
                      sum(st.absorbed) + sum(st.stopped) + sum(st.roulette);
  EXPECT_NEAR(ends, sum(st.emitted), 1e-5 * sum(st.emitted));
  EXPECT_EQ(sum(st.absorbed), 0.0);
  EXPECT_LT(sum(st.direct), 1e-4 * sum(st.emitted));  // the cone is the ball: nothing misses it
  EXPECT_LT(sum(st.cut), 1e-3 * sum(st.emitted));  // max_depth only (roulette replaces min_weight)
  const double sigma = std::sqrt(sum(st.roulette_variance));
  EXPECT_GT(sigma, 0.0);
  EXPECT_NEAR(sum(st.stored) + sum(st.escaped), sum(st.emitted),
              4 * sigma + 1e-3 * sum(st.emitted));
  EXPECT_NEAR(sum(st.roulette), 0.0, 4 * sigma);
  EXPECT_GT(sum(st.stored), 0.8 * sum(st.emitted));
  ASSERT_EQ(map.maps().size(), 1u);
  EXPECT_EQ(st.photons_stored, map.maps()[0].size());
  std::printf(
      "floor %.6f + sky %.6f = %.6f of the cone's power; roulette net %.2e (sigma %.2e), cut "
      "%.2e\n",
      sum(st.stored) / sum(st.emitted), sum(st.escaped) / sum(st.emitted),
      (sum(st.stored) + sum(st.escaped)) / sum(st.emitted), sum(st.roulette) / sum(st.emitted),
      sigma / sum(st.emitted), sum(st.cut) / sum(st.emitted));
}

// Units. A thin wide slab (n = 1.31, thickness t = 0.1) between an inverse-square point light at
// height H = 5 and the floor: below the light the floor gets E = T I / (H - t (1 - 1/n))^2, T =
// (1 - R)^2 / (1 - R^2) (all internal reflections; paraxial: the slab moves the apparent source
// by t (1 - 1/n), Hecht sec. 5.2.3), in the direct light's units (I cos(theta) / d^2).
// Tolerance: N photons fill the cone of the box's bounding sphere (radius R_b, centre at D from
// the light), about a disc of radius R_b H / D on the floor, so the kernel's disc of radius r
// holds K = N (r D / (R_b H))^2 photons. A Poisson photon set would give a relative standard
// deviation 1/sqrt(0.75 K) (the Epanechnikov weights' effective count (sum w)^2 / sum w^2 is
// 0.75 K); Halton points are more uniform than random ones, so 3 sigma_Poisson bounds the error
// safely (6.6 % here; the measured error is printed, ~5e-4). The kernel's own bias, from E's
// curvature over r, is ~ (r / H)^2 = 4e-4.
TEST(CausticMap, SameUnitsAsDirectLight) {
  const double n = 1.31, t = 0.1, height = 5.0, intensity = 100.0, radius = 0.1, photons = 200000;
  const Scene scene = scene_from(R"(
[caustics]
photons = 200000
radius = 0.1
[[lights]]
position = [0.0, 4.0, 0.0]
intensity = 100.0
falloff = "inverse_square"
[media.ice]
ior = 1.31
[materials.white]
kind = "matte"
[[objects]]
shape = "box"
min = [-0.5, 0.0, -0.5]
max = [0.5, 0.1, 0.5]
inside = "ice"
outside = "vacuum"
[[objects]]
shape = "plane"
point = [0.0, -1.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "white"
)" + test::kCamera);
  const CausticMap map = CausticMap::build(scene, 2);
  const double r = std::pow((n - 1) / (n + 1), 2);
  const double transmitted = (1 - r) * (1 - r);  // the second pass, R^2 = 3e-4, is below min_weight
  const double expected = transmitted * intensity / std::pow(height - t * (1 - 1 / n), 2);
  const double bound_radius = std::sqrt(0.5 * 0.5 + 0.05 * 0.05 + 0.5 * 0.5), distance = 3.95;
  const double k = photons * std::pow(radius * distance / (bound_radius * height), 2);
  const double tolerance = 3 / std::sqrt(0.75 * k);
  const Rgb e = map.irradiance({0, -1, 0}, {0, 1, 0});
  EXPECT_NEAR(e.r, expected, tolerance * expected);
  EXPECT_NEAR(e.b, expected, tolerance * expected);
  std::printf("slab caustic E = %.6f, expected %.6f (rel. error %.2e, tolerance %.2e)\n", e.r,
              expected, e.r / expected - 1, tolerance);
}

/// The units test's slab and floor, lit by `light` (a [[lights]] table's keys).
Scene slab_scene(const std::string& light, const std::string& caustics) {
  return scene_from("[caustics]\n" + caustics + "\n[[lights]]\n" + light + R"(
[media.ice]
ior = 1.31
[materials.white]
kind = "matte"
[[objects]]
shape = "box"
min = [-0.5, 0.0, -0.5]
max = [0.5, 0.1, 0.5]
inside = "ice"
outside = "vacuum"
[[objects]]
shape = "plane"
point = [0.0, -1.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "white"
)" + test::kCamera);
}

// A sphere light (radius a = 0.3, intensity I: radiance L = I / (pi a^2)) sends photons from its
// whole disc into the cone of the target's sphere grown by a: the power sent is I Omega(R + a),
// and under the slab's centre, lit through the slab by the whole light, the caustic is the
// point light's T I / (H - t (1 - 1/n))^2 up to the light's extent, O((a / H)^2) = 0.4 % (the
// irradiance of a uniform sphere is exactly I / d^2 for an unoccluded receiver; the slab's
// paraxial shift is what makes it approximate). Noise bound as in the units test, 3 sigma of a
// Poisson set of the K photons in the disc.
TEST(CausticMap, SphereLightSameCausticAsPointLight) {
  const Scene point =
      slab_scene("position = [0.0, 4.0, 0.0]\nintensity = 100.0\nfalloff = \"inverse_square\"",
                 "photons = 200000\nradius = 0.1");
  const Scene sphere = slab_scene(
      "kind = \"sphere\"\nradius = 0.3\nposition = [0.0, 4.0, 0.0]\nintensity = 100.0\nfalloff = "
      "\"inverse_square\"",
      "photons = 200000\nradius = 0.1");
  ASSERT_EQ(sphere.sphere_lights().size(), 1u);
  const CausticMap a = CausticMap::build(point, 2), b = CausticMap::build(sphere, 2);
  const double bound = std::sqrt(0.5 * 0.5 + 0.05 * 0.05 + 0.5 * 0.5), d = 3.95,
               grown = bound + 0.3;
  const double omega = 2 * M_PI * (1 - std::sqrt(1 - grown * grown / (d * d)));
  EXPECT_NEAR(b.statistics().emitted.g, 100.0 * omega, 1e-4 * 100.0 * omega);
  const double k = 200000.0 * std::pow(0.1 * d / (grown * 5.0), 2);
  const double tolerance = 3 / std::sqrt(0.75 * k) + 4e-3;
  const float ea = a.irradiance({0, -1, 0}, {0, 1, 0}).g,
              eb = b.irradiance({0, -1, 0}, {0, 1, 0}).g;
  EXPECT_NEAR(eb, ea, tolerance * ea);
  std::printf("sphere light caustic %.5f vs point light %.5f (rel. %.2e, tolerance %.2e)\n", eb, ea,
              eb / ea - 1, tolerance);
  // The penumbra: at the slab's shadow edge (x = 0.5 on the slab, 0.5 * 5 / 4 = 0.625 on the
  // floor) the point light's caustic ends within the kernel radius, the sphere light's fades over
  // a (H - h_slab) / h_slab = 0.3 * 1.05 / 4 wide band: there is still light beyond the point's.
  EXPECT_EQ(a.irradiance({0.75f, -1, 0}, {0, 1, 0}).g, 0.0f);
  EXPECT_GT(b.irradiance({0.68f, -1, 0}, {0, 1, 0}).g, 0.0f);
}

// Two targets: a small glass ball and a wide thin slab beside it. Each gets its own map and
// radius, photons shared in proportion to sqrt(power), so the small target's kernel is finer.
TEST(CausticMap, EachTargetHasItsOwnRadius) {
  const Scene scene =
      ball_over_floor("ior = 1.5", -1.0, "[0.0, 6.0, 0.0]", "", "photons = 100000", R"(
[[objects]]
shape = "box"
min = [2.0, -0.5, -2.0]
max = [6.0, -0.45, 2.0]
inside = "glass"
outside = "vacuum"
)");
  const CausticMap map = CausticMap::build(scene, 2);
  const auto& t = map.statistics().targets;
  ASSERT_EQ(t.size(), 2u);
  ASSERT_EQ(map.maps().size(), 2u);
  EXPECT_LT(t[0].radius, t[1].radius);
  EXPECT_NEAR(t[0].radius, 1.0 * std::sqrt(kPhotonsPerDisc / double(t[0].photons_traced)), 1e-4);
  EXPECT_GT(t[0].photons_stored, 0u);
  EXPECT_GT(t[1].photons_stored, 0u);
  EXPECT_EQ(t[0].photons_traced + t[1].photons_traced, 100000);
  // Under the slab (x = 4): its light, through the slab; no photon of the ball's map there.
  EXPECT_GT(map.maps()[1].irradiance({4.0f, -1.0f, 0.0f}, {0, 1, 0}).g, 0.0f);
}

// Lights without falloff (the POV-Ray convention): photons carry I D^2 Omega / N, D the distance
// to the target's centre, so the same slab gives D^2 times the inverse-square light's caustic.
TEST(CausticMap, LightWithoutFalloffMatchesAtTheTargetsDistance) {
  auto slab = [](const std::string& falloff) {
    return scene_from(R"(
[caustics]
photons = 50000
radius = 0.05
[[lights]]
position = [0.0, 4.0, 0.0]
falloff = ")" + falloff +
                      R"("
[media.ice]
ior = 1.31
[materials.white]
kind = "matte"
[[objects]]
shape = "box"
min = [-0.5, 0.0, -0.5]
max = [0.5, 0.1, 0.5]
inside = "ice"
outside = "vacuum"
[[objects]]
shape = "plane"
point = [0.0, -1.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "white"
)" + test::kCamera);
  };
  const CausticMap inverse_square = CausticMap::build(slab("inverse_square"), 2);
  const CausticMap none = CausticMap::build(slab("none"), 2);
  const double d = 4.0 - 0.05;  // light to the box's centre
  const Rgb a = inverse_square.irradiance({0, -1, 0}, {0, 1, 0}),
            b = none.irradiance({0, -1, 0}, {0, 1, 0});
  ASSERT_GT(a.g, 0.0f);
  EXPECT_NEAR(b.g / a.g, d * d, 1e-5 * d * d);  // the same photons, scaled
}

// A ball lens under a point light at s = 6 R from its centre images the light at s' = 1/(1/f -
// 1/s) below the centre (f = n R / (2 (n - 1))). With the floor there, the caustic's peak is on
// the axis: the irradiance at the axis point exceeds that at every point of a grid around it
// farther than 2 radii of the estimate (the estimate smooths the peak over r), and it is
// concentrated: many times the unobstructed light I / (s + s')^2 there. With the floor 40 %
// nearer or farther than s' the peak is lower (the paraxial focus is where the concentration is
// highest for a kernel radius much smaller than the ball).
TEST(CausticMap, BallLensFocusOnTheFloor) {
  const double n = 1.31, f = n / (2 * (n - 1)), s = 6.0, s_image = 1.0 / (1.0 / f - 1.0 / s);
  auto peak = [&](double floor_distance) {
    const Scene scene = ball_over_floor("ior = " + std::to_string(n), -floor_distance,
                                        "[0.0, 6.0, 0.0]", "", "photons = 100000\nradius = 0.02");
    const CausticMap map = CausticMap::build(scene, 2);
    return map.irradiance({0, float(-floor_distance), 0}, {0, 1, 0}).g;
  };
  const double at_focus = peak(s_image);
  const double unobstructed = 100.0 / std::pow(s + s_image, 2);
  EXPECT_GT(at_focus, 20 * unobstructed);
  EXPECT_GT(at_focus, peak(0.6 * s_image));
  EXPECT_GT(at_focus, peak(1.4 * s_image));
  // On the focal plane the axis point is the maximum.
  const Scene scene = ball_over_floor("ior = " + std::to_string(n), -s_image, "[0.0, 6.0, 0.0]", "",
                                      "photons = 100000\nradius = 0.02");
  const CausticMap map = CausticMap::build(scene, 2);
  for (int i = -10; i <= 10; ++i)
    for (int k = -10; k <= 10; ++k) {
      const float x = 0.01f * float(i), z = 0.01f * float(k);
      if (x * x + z * z < 4 * 0.02f * 0.02f) continue;
      EXPECT_LT(map.irradiance({x, float(-s_image), z}, {0, 1, 0}).g, at_focus) << x << " " << z;
    }
}

// The caustic of a sphere is symmetric about the line from the light through its centre, so its
// power-weighted centroid on the floor lies in the vertical plane through the light and the
// centre, and for a light straight above it lies on the axis. Tolerance: for N stored photons
// of spread sigma (the caustic's lateral standard deviation), the centroid of a Poisson set
// varies by sigma / sqrt(N); 4 of those (Halton is more uniform) + 1e-5 for float sums.
TEST(CausticMap, CentroidOnTheLineFromTheLightThroughTheCentre) {
  for (const std::string light : {"[0.0, 6.0, 0.0]", "[-4.0, 6.0, 4.0]"}) {
    const Scene scene = ball_over_floor("ior = 1.31", -1.0, light, "", "photons = 50000");
    const CausticMap map = CausticMap::build(scene, 2);
    double w = 0, cx = 0, cz = 0, cxx = 0, czz = 0;
    for (const Photon& p : map.maps()[0].photons()) {
      const double pw = p.power.g;
      w += pw;
      cx += pw * p.position.x;
      cz += pw * p.position.z;
      cxx += pw * p.position.x * p.position.x;
      czz += pw * p.position.z * p.position.z;
    }
    cx /= w;
    cz /= w;
    const double sigma = std::sqrt(cxx / w - cx * cx + czz / w - cz * cz);
    const double tol = 4 * sigma / std::sqrt(double(map.maps()[0].size())) + 1e-5;
    // Distance from the centroid to the vertical plane through the light and the centre (both
    // lie on the line x = -z for the oblique light, on x = z = 0 for the light above).
    if (light == "[0.0, 6.0, 0.0]") {
      EXPECT_NEAR(cx, 0.0, tol);
      EXPECT_NEAR(cz, 0.0, tol);
    } else {
      EXPECT_NEAR((cx + cz) / std::sqrt(2.0), 0.0, tol);
      EXPECT_GT(cx, 0.0);  // away from the light (x = -4)
    }
  }
}

// An index-matched sphere (n = 1 in vacuum) beside a glass one is no photon target, and the
// glass sphere's caustic (its reflections reach everywhere) is the same with or without it:
// photons crossing it keep their direction to float rounding (1e-4 covers the shifts of ~1e-7
// in position against the kernel's radius 0.02).
TEST(CausticMap, IndexMatchedSphereChangesNothing) {
  const std::string matched = R"(
[media.matched]
ior = 1.0
[[objects]]
shape = "sphere"
center = [2.5, 0.0, 0.0]
radius = 1.0
inside = "matched"
outside = "vacuum"
)";
  const Scene with = ball_over_floor("ior = 1.5", -1.0, "[0.0, 6.0, 0.0]", "",
                                     "photons = 20000\nradius = 0.2", matched);
  const Scene without =
      ball_over_floor("ior = 1.5", -1.0, "[0.0, 6.0, 0.0]", "", "photons = 20000\nradius = 0.2");
  ASSERT_TRUE(with.objects()[2].index_matched);
  const CausticMap a = CausticMap::build(with, 2), b = CausticMap::build(without, 2);
  EXPECT_EQ(a.statistics().cones, 1);
  EXPECT_EQ(a.statistics().photons_stored, b.statistics().photons_stored);
  int lit = 0;
  for (int i = 0; i <= 40; ++i) {
    const Vec3 p{1.0f + 0.075f * float(i), -1.0f, 0.1f};
    const float ea = a.irradiance(p, {0, 1, 0}).g, eb = b.irradiance(p, {0, 1, 0}).g;
    EXPECT_NEAR(ea, eb, 1e-4 * eb) << p.x;
    lit += eb > 0 ? 1 : 0;
  }
  EXPECT_GT(lit, 20);  // the reflected caustic reaches under the matched sphere
}

// Spectral scene, white light: each photon carries one wavelength and its power is the sRGB of
// the light's spectrum there, normalised per cone so that the photons sent sum exactly to the
// light's colour (white) times I Omega (a ratio estimator, as the spectral film's): float sums,
// 1e-5. Without the normalisation the Halton quadrature of the CIE x D65 integrand is off by
// ~1e-3.
TEST(CausticMap, WhiteLightPhotonsSumToWhite) {
  const Scene scene =
      ball_over_floor("preset = \"n-bk7\"", -1.0, "[0.0, 6.0, 0.0]", "", "photons = 100000");
  ASSERT_TRUE(scene.spectral());
  const CausticMap map = CausticMap::build(scene, 2);
  ASSERT_TRUE(photons_carry_wavelengths(scene));  // N-BK7 disperses
  const double omega = 2 * M_PI * (1 - std::sqrt(1 - 1.0 / 36.0)), power = 100.0 * omega;
  const CausticStatistics& st = map.statistics();
  EXPECT_NEAR(st.emitted.r, power, 1e-5 * power);
  EXPECT_NEAR(st.emitted.g, power, 1e-5 * power);
  EXPECT_NEAR(st.emitted.b, power, 1e-5 * power);
}

// The same map for 1 and 2 threads: same photons in the same order, same statistics.
TEST(CausticMap, IndependentOfThreadCount) {
  const Scene scene =
      ball_over_floor("preset = \"ice-ih\"", -1.0, "[-4.0, 6.0, 4.0]", "", "photons = 30000");
  const CausticMap one = CausticMap::build(scene, 1), two = CausticMap::build(scene, 2);
  ASSERT_EQ(one.maps()[0].photons().size(), two.maps()[0].photons().size());
  for (std::size_t i = 0; i < one.maps()[0].photons().size(); ++i) {
    const Photon &a = one.maps()[0].photons()[i], &b = two.maps()[0].photons()[i];
    ASSERT_EQ(a.position.x, b.position.x);
    ASSERT_EQ(a.position.z, b.position.z);
    ASSERT_EQ(a.power.r, b.power.r);
    ASSERT_EQ(a.power.b, b.power.b);
    ASSERT_EQ(a.inv_radius2, b.inv_radius2);
  }
  EXPECT_EQ(one.statistics().stored.g, two.statistics().stored.g);
  EXPECT_EQ(one.statistics().escaped.r, two.statistics().escaped.r);
}

// Settings: disabled -> no map; automatic count and radius follow the documented rule.
TEST(CausticMap, SettingsAndAutomaticRule) {
  EXPECT_TRUE(CausticMap::build(
                  ball_over_floor("ior = 1.31", -1.0, "[0.0, 6.0, 0.0]", "", "enabled = false"))
                  .empty());
  const CausticMap map =
      CausticMap::build(ball_over_floor("ior = 1.31", -1.0, "[0.0, 6.0, 0.0]"), 2);
  EXPECT_EQ(map.statistics().photons_traced, kDefaultPhotons);
  EXPECT_NEAR(map.statistics().targets[0].radius,
              1.0 * std::sqrt(kPhotonsPerDisc / double(kDefaultPhotons)), 1e-5);
}

// bench/render/ray_limit tells the photon pass's rays from the frame's by the stream the pass
// marks (render/accel/ray_record.h): every query of the pass arrives marked photon (at least one
// closest-hit query per photon traced), and the mark is back to frame when the pass returns.
TEST(CausticMap, MarksItsRaysAsThePhotonStream) {
  struct Log final : RayRecorder {
    RayStream now = RayStream::frame;
    long long photon = 0, frame = 0, marks = 0;
    void record(RayQuery, const Ray&) noexcept override {
      ++(now == RayStream::photon ? photon : frame);
    }
    void stream(RayStream s) noexcept override {
      now = s;
      ++marks;
    }
  };
  const Scene scene = ball_over_floor("ior = 1.31", -1.0, "[0.0, 6.0, 0.0]", "", "photons = 2000");
  Log log;
  set_ray_recorder(&log);
  const CausticMap map = CausticMap::build(scene, 1);
  set_ray_recorder(nullptr);
  EXPECT_EQ(log.frame, 0);
  EXPECT_GE(log.photon, map.statistics().photons_traced);
  EXPECT_GT(map.statistics().photons_traced, 0);
  EXPECT_EQ(log.marks, 2);
  EXPECT_EQ(log.now, RayStream::frame);
}

}  // namespace
}  // namespace thaw::render::photon
