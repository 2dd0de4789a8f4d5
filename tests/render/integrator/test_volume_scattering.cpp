// Tests volume scattering in dielectric media (render/media/scattering.h, the integrators'
// scatter()): lossless scattering inside an ice ball under a uniform surround is invisible (the
// furnace, RGB and spectral, forward and isotropic phases), and a slab's total transmittance and
// reflectance at normal incidence match an independent Monte Carlo simulation written here (a 1D
// random walk with Henyey-Greenstein scattering and exact Fresnel at both faces, total internal
// reflection included), for several optical thicknesses and asymmetries. Tolerances: 1 % (of the
// surround, of the incident light), with the estimates' standard error at least five times
// smaller.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "render/integrator/whitted.h"
#include "render/math/rng.h"
#include "render/media/scattering.h"
#include "render/scene/scene.h"
#include "tests/render/test_util.h"

namespace thaw::render {
namespace {

MediumDescription cloudy(const std::string& name, double ior, double sigma_s, double g) {
  MediumDescription m = test::medium(name, ior);
  media::MediumSpec spec;
  spec.name = name;
  spec.ior = media::IorModel::constant(ior);
  spec.scattering_per_m = sigma_s;
  spec.asymmetry = g;
  m.spec = spec;
  return m;
}

struct Stats {
  double mean, error;
};
Stats pixel_stats(const Image& img) {
  double s = 0, s2 = 0;
  const auto n = double(img.pixels().size());
  for (const Rgb& c : img.pixels()) {
    const double v = (double(c.r) + c.g + c.b) / 3.0;
    s += v;
    s2 += v * v;
  }
  const double mean = s / n;
  return {mean, std::sqrt(std::max(0.0, s2 / n - mean * mean) / (n - 1))};
}

struct FurnaceCase {
  double sigma_s, g;
  bool spectral;
};
class ScatteringFurnace : public ::testing::TestWithParam<FurnaceCase> {};

TEST_P(ScatteringFurnace, LosslessCloudyBallIsInvisible) {
  const FurnaceCase c = GetParam();
  SceneDescription d;
  // Next-event estimation makes each sample a little noisy (the furnace of analog tracking has
  // none): 48 x 48 x 64 samples bring the standard error below 1e-3.
  d.image.width = d.image.height = 48;
  d.image.samples_per_pixel = 64;
  d.image.adaptive = false;
  d.image.background = {0.5, 0.5, 0.5};
  d.image.max_depth = 256;
  d.image.min_weight = 1e-6;
  d.image.spectral = c.spectral ? ImageSettings::Spectral::on : ImageSettings::Spectral::off;
  d.caustics.enabled = false;
  d.camera.position = {0.0, 0.0, 2.2};
  d.camera.look_at = {0.0, 0.0, 0.0};
  d.camera.vertical_fov_deg = 40.0;  // the ball fills the frame
  d.media = {test::medium("air", 1.0), cloudy("ice", 1.31, c.sigma_s, c.g)};
  ObjectDescription o;
  o.shape = ObjectDescription::Shape::sphere;
  o.radius = 1.0;
  o.inside = "ice";
  o.outside = "air";
  d.objects.push_back(o);
  const Stats st = pixel_stats(render(build_scene(d)).image);
  std::printf("furnace sigma_s %.1f g %.2f%s: mean %.5f +- %.5f\n", c.sigma_s, c.g,
              c.spectral ? " spectral" : "", st.mean, st.error);
  ASSERT_LT(5.0 * st.error, 0.005);
  EXPECT_NEAR(st.mean, 0.5, 0.005);
}

INSTANTIATE_TEST_SUITE_P(Media, ScatteringFurnace,
                         ::testing::Values(FurnaceCase{3.0, 0.86, false},
                                           FurnaceCase{3.0, 0.0, false},
                                           FurnaceCase{1.0, -0.3, false},
                                           FurnaceCase{3.0, 0.86, true}));

// ---- The slab against an independent Monte Carlo ----

/// Unpolarised Fresnel reflectance from the side of index n1 into n2 at cosine mu (Hecht 4.6),
/// written again here so the reference shares no code with the renderer.
double fresnel_reference(double mu, double n1, double n2) {
  const double s2 = (n1 / n2) * (n1 / n2) * (1 - mu * mu);
  if (s2 >= 1) return 1;
  const double ct = std::sqrt(1 - s2);
  const double rs = (n1 * mu - n2 * ct) / (n1 * mu + n2 * ct);
  const double rp = (n2 * mu - n1 * ct) / (n2 * mu + n1 * ct);
  return 0.5 * (rs * rs + rp * rp);
}

struct SlabResult {
  double t, r, t_error, r_error;
};

/// A slab of thickness 1 m, index n, in vacuum, lit at normal incidence: a photon random walk
/// in depth z alone (an infinite slab), Henyey-Greenstein turns, Fresnel at each face by a coin.
SlabResult slab_reference(double n, double sigma_s, double g, int photons) {
  Pcg32 rng(2024);
  long long transmitted = 0, reflected = 0;
  for (int i = 0; i < photons; ++i) {
    if (rng.next_float() < fresnel_reference(1.0, 1.0, n)) {
      ++reflected;
      continue;
    }
    double z = 1.0, mu = -1.0;  // z = 1 the top face; travelling down
    for (int k = 0; k < 100000; ++k) {
      const double s = -std::log(1.0 - double(rng.next_float())) / sigma_s;
      const double z_new = z + mu * s;
      if (z_new < 0.0 || z_new > 1.0) {
        const bool bottom = z_new < 0.0;
        if (rng.next_float() < fresnel_reference(std::abs(mu), n, 1.0)) {
          z = bottom ? 0.0 : 1.0;
          mu = -mu;
          continue;
        }
        (bottom ? transmitted : reflected) += 1;
        break;
      }
      z = z_new;
      // Henyey-Greenstein cosine to the old direction, uniform azimuth.
      const double u = rng.next_float();
      const double c = std::abs(g) < 1e-3
                           ? 1 - 2 * u
                           : (1 + g * g - std::pow((1 - g * g) / (1 - g + 2 * g * u), 2)) / (2 * g);
      const double phi = 2 * std::numbers::pi * rng.next_float();
      mu = mu * c + std::sqrt(std::max(0.0, 1 - mu * mu)) * std::sqrt(std::max(0.0, 1 - c * c)) *
                        std::cos(phi);
    }
  }
  const double t = double(transmitted) / photons, r = double(reflected) / photons;
  return {t, r, std::sqrt(t * (1 - t) / photons), std::sqrt(r * (1 - r) / photons)};
}

/// The renderer's view of the same slab: a camera looking straight down through a 1 m box
/// (80 m wide) at an emitting plane below (transmittance) or with an emitting plane above it
/// (reflectance), everything else black.
Stats slab_render(double n, double sigma_s, double g, bool transmittance) {
  SceneDescription d;
  d.image.width = d.image.height = 48;
  d.image.samples_per_pixel = 96;
  d.image.adaptive = false;
  d.image.max_depth = 256;
  d.image.min_weight = 1e-6;
  d.image.spectral = ImageSettings::Spectral::off;
  d.caustics.enabled = false;
  d.camera.position = {0.0, 3.0, 0.0};
  d.camera.look_at = {0.0, 0.0, 0.0};
  d.camera.up = {0.0, 0.0, -1.0};
  d.camera.vertical_fov_deg = 0.5;
  d.media = {test::medium("air", 1.0), cloudy("cloud", n, sigma_s, g)};
  MaterialDescription lamp;
  lamp.name = "lamp";
  lamp.kind = MaterialDescription::Kind::emissive;
  lamp.emission = {1.0, 1.0, 1.0};
  d.materials.push_back(lamp);
  ObjectDescription slab;
  slab.shape = ObjectDescription::Shape::box;
  slab.box_min = {-40.0, 0.0, -40.0};
  slab.box_max = {40.0, 1.0, 40.0};
  slab.inside = "cloud";
  slab.outside = "air";
  d.objects.push_back(slab);
  ObjectDescription plane;
  plane.shape = ObjectDescription::Shape::plane;
  plane.material = "lamp";
  plane.point = {0.0, transmittance ? -1.0 : 5.0, 0.0};
  plane.normal = {0.0, transmittance ? 1.0 : -1.0, 0.0};
  d.objects.push_back(plane);
  return pixel_stats(render(build_scene(d)).image);
}

struct SlabCase {
  double n, sigma_s, g;
};
class SlabAgainstReference : public ::testing::TestWithParam<SlabCase> {};

TEST_P(SlabAgainstReference, TotalTransmittanceAndReflectance) {
  const SlabCase c = GetParam();
  const SlabResult ref = slab_reference(c.n, c.sigma_s, c.g, 1000000);
  const Stats t = slab_render(c.n, c.sigma_s, c.g, true);
  const Stats r = slab_render(c.n, c.sigma_s, c.g, false);
  // Nothing is absorbed: what is not transmitted is reflected (the lateral leak through the
  // box's sides is below 1e-4 at these optical thicknesses).
  EXPECT_NEAR(t.mean + r.mean, 1.0, 0.01);
  // Within 1 % of the incident light, each estimate's combined standard error at least five
  // times smaller than that.
  const double t_error = std::hypot(t.error, ref.t_error);
  const double r_error = std::hypot(r.error, ref.r_error);
  ASSERT_LT(5.0 * t_error, 0.01);
  ASSERT_LT(5.0 * r_error, 0.01);
  EXPECT_NEAR(t.mean, ref.t, 0.01) << "reference " << ref.t;
  EXPECT_NEAR(r.mean, ref.r, 0.01) << "reference " << ref.r;
  std::printf("slab n %.2f sigma_s %.1f g %.2f: T %.4f (reference %.4f), R %.4f (%.4f)\n", c.n,
              c.sigma_s, c.g, t.mean, ref.t, r.mean, ref.r);
}

INSTANTIATE_TEST_SUITE_P(Slabs, SlabAgainstReference,
                         ::testing::Values(SlabCase{1.31, 1.0, 0.86}, SlabCase{1.31, 2.0, 0.0},
                                           SlabCase{1.0, 1.5, 0.5}));

// ---- Next-event estimation against the single-scattering integral ----

/// Distance from p along unit direction w to the surface of the box [lo, hi] that contains p.
double box_exit(const Vec3d& p, const Vec3d& w, const Vec3d& lo, const Vec3d& hi) {
  double t = 1e300;
  for (std::size_t i = 0; i < 3; ++i) {
    if (w[i] > 0) t = std::min(t, (hi[i] - p[i]) / w[i]);
    if (w[i] < 0) t = std::min(t, (lo[i] - p[i]) / w[i]);
  }
  return t;
}

struct NeeCase {
  bool sphere;
  double g;
};
class ScatteringNextEvent : public ::testing::TestWithParam<NeeCase> {};

// An optically thin cloudy box with the index of its surround (the approximation of the
// shadow rays is exact there), seen along its axis, lit from the side by a point or a small
// sphere light, which no camera path can hit (a point) or only rarely: its light comes by
// next-event estimation. Reference: the single-scattering integral along the camera ray,
// L = int_0^D sigma_s p(cos) I / d^2 exp(-sigma_s (t + s_l)) dt (s_l the path to the light
// inside the box), by the midpoint rule with 20000 steps. Multiple scattering adds at most
// the chance of a second event before leaving, 1 - exp(-sigma_s * longest chord) = 0.35 %
// (sigma_s 0.002 /m, chord sqrt(3) m); tolerance 1 % of the reference with the estimate's
// standard error at least 3 times smaller.
TEST_P(ScatteringNextEvent, ThinCloudMatchesTheSingleScatteringIntegral) {
  const NeeCase c = GetParam();
  const double sigma_s = 0.002, intensity = 50.0;
  const Vec3d lo{-0.5, -0.5, -0.5}, hi{0.5, 0.5, 0.5}, light{1.5, 0.8, 0.2};
  SceneDescription d;
  d.image.width = d.image.height = 8;
  d.image.samples_per_pixel = 256;
  d.image.adaptive = false;
  d.image.filter = FilterKind::box;
  d.image.filter_radius = 0.5;
  d.image.max_depth = 64;
  d.image.min_weight = 1e-9;
  d.image.spectral = ImageSettings::Spectral::off;
  d.caustics.enabled = false;
  d.camera.position = {0.0, 0.0, 3.0};
  d.camera.look_at = {0.0, 0.0, 0.0};
  d.camera.vertical_fov_deg = 0.01;  // every ray along the axis to 1e-6 rad
  d.media = {test::medium("air", 1.0), cloudy("cloud", 1.0, sigma_s, c.g)};
  ObjectDescription box;
  box.shape = ObjectDescription::Shape::box;
  box.box_min = lo;
  box.box_max = hi;
  box.inside = "cloud";
  box.outside = "air";
  d.objects.push_back(box);
  LightDescription l;
  l.kind = c.sphere ? LightDescription::Kind::sphere : LightDescription::Kind::point;
  l.radius = c.sphere ? 0.01 : 0.0;
  l.position = light;
  l.intensity = intensity;
  l.falloff = LightDescription::Falloff::inverse_square;
  d.lights.push_back(l);
  const Stats st = pixel_stats(render(build_scene(d)).image);
  // Single scattering along the camera ray (0, 0, 0.5) -> (0, 0, -0.5), travelling along -z.
  double ref = 0.0;
  const int steps = 20000;
  const double dt = 1.0 / steps;
  for (int i = 0; i < steps; ++i) {
    const double t = (i + 0.5) * dt;
    const Vec3d p{0.0, 0.0, 0.5 - t};
    const Vec3d to{light[0] - p[0], light[1] - p[1], light[2] - p[2]};
    const double dist2 = to[0] * to[0] + to[1] * to[1] + to[2] * to[2], dist = std::sqrt(dist2);
    const Vec3d w{to[0] / dist, to[1] / dist, to[2] / dist};
    // The light travels along -w, then towards the camera (+z): cos = -w_z.
    const double cos = -w[2];
    const double phase =
        (1 - c.g * c.g) / (4 * std::numbers::pi * std::pow(1 + c.g * c.g - 2 * c.g * cos, 1.5));
    const double s_l = box_exit(p, w, lo, hi);
    ref += sigma_s * phase * intensity / dist2 * std::exp(-sigma_s * (t + s_l)) * dt;
  }
  std::printf("next event (%s light, g %.2f): %.6g +- %.2g, single scattering %.6g\n",
              c.sphere ? "sphere" : "point", c.g, st.mean, st.error, ref);
  ASSERT_LT(3.0 * st.error, 0.01 * ref);
  EXPECT_NEAR(st.mean, ref, 0.01 * ref);
}

INSTANTIATE_TEST_SUITE_P(Lights, ScatteringNextEvent,
                         ::testing::Values(NeeCase{false, 0.0}, NeeCase{false, 0.86},
                                           NeeCase{true, 0.5}));

TEST(Scattering, BubblesGiveTheGeometricOpticsCoefficient) {
  // f = 1e-3, r = 50 um: 1.5 f / r = 30 /m (a mean free path of 3.3 cm).
  EXPECT_DOUBLE_EQ(media::bubble_scattering_per_m(1e-3, 50e-6), 30.0);
  EXPECT_TRUE(media::asymmetry_problem(1.0).has_value());
  EXPECT_TRUE(media::asymmetry_problem(-1.0).has_value());
  EXPECT_FALSE(media::asymmetry_problem(0.86).has_value());
  EXPECT_TRUE(media::scattering_problem(-1.0).has_value());
  EXPECT_TRUE(media::air_fraction_problem(1.0).has_value());
  EXPECT_FALSE(media::air_fraction_problem(0.001).has_value());
}

}  // namespace
}  // namespace thaw::render
