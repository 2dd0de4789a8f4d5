#include "render/light/sphere_light.h"

#include <gtest/gtest.h>

#include <cmath>

#include "render/scene/scene.h"
#include "tests/render/sampling/sampling_test_util.h"

namespace thaw::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The closed form under test (render/light/sphere_light.h).
double snyder_irradiance(double cos_theta, double sin2_sigma) {
  return sphere_irradiance_per_radiance(cos_theta, sin2_sigma);
}

struct Estimate {
  double mean = 0, standard_error = 0;
};

/// Irradiance at p (normal n) from `light` by n stratified low-discrepancy samples, with the
/// Monte Carlo standard error of the mean (the sample deviation / sqrt(n)).
Estimate estimate_irradiance(const SphereLight& light, Vec3 p, Vec3 n, int count) {
  const sampling::PixelSampler sampler(3, 5, 11);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < count; ++i) {
    SphereLightSample s;
    EXPECT_TRUE(sample_sphere_light(light, p, sampler.get_2d(static_cast<std::uint32_t>(i), 1), s));
    const double v = double(s.radiance.g) * std::max(0.0f, dot(s.wi, n)) / s.pdf;
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / count,
               var = std::max(0.0, sum2 / count - mean * mean) * count / (count - 1);
  return {mean, std::sqrt(var / count)};
}

SphereLight light_at(Vec3 c, float r, float intensity, bool inverse_square = true) {
  return {c, r, sphere_light_radiance(Rgb::gray(intensity), r), inverse_square, 4};
}

TEST(SphereLight, FullyVisibleSphereGivesThePointLightIrradiance) {
  // E = I cos(theta) / d^2 exactly for L = I / (pi r^2). Tolerance: 5 Monte Carlo standard errors
  // of the estimate itself (stratified samples only do better) plus float rounding (1e-5).
  const float intensity = 3.0f;
  for (float r : {0.01f, 0.3f, 0.9f})
    for (double theta_deg : {0.0, 20.0, 40.0}) {
      const double th = theta_deg * kPi / 180.0;
      const Vec3 n{float(std::sin(th)), float(std::cos(th)), 0.0f};
      const SphereLight light = light_at({0, 2, 0}, r, intensity);
      const Estimate e = estimate_irradiance(light, {0, 0, 0}, n, 256);
      const double exact = intensity * std::cos(th) / 4.0;
      EXPECT_NEAR(e.mean, exact, 5 * e.standard_error + 1e-5 * exact) << r << " " << theta_deg;
    }
}

TEST(SphereLight, HorizonStraddlingSphereMatchesSnydersClosedForm) {
  // Tilt the surface until the sphere (half-angle sigma = asin(r/d)) is cut by the horizon:
  // samples below it contribute nothing, and the mean must approach Snyder's formula.
  const float r = 1.2f, intensity = 5.0f;
  const double d = 2.0, sin2_sigma = (r * r) / (d * d), sigma = std::asin(std::sqrt(sin2_sigma));
  const SphereLight light = light_at({0, float(d), 0}, r, intensity);
  const double L = intensity / (kPi * r * r);
  for (double theta :
       {kPi / 2 - sigma - 0.05, kPi / 2 - 0.3, kPi / 2, kPi / 2 + 0.3, kPi / 2 + sigma - 0.05}) {
    const Vec3 n{float(std::sin(theta)), float(std::cos(theta)), 0.0f};
    const Estimate e = estimate_irradiance(light, {0, 0, 0}, n, 1024);
    const double exact = L * snyder_irradiance(std::cos(theta), sin2_sigma);
    EXPECT_GT(exact, 0.0);
    EXPECT_NEAR(e.mean, exact, 5 * e.standard_error + 1e-5 * L) << theta;
  }
  // Entirely below the horizon: nothing.
  EXPECT_EQ(estimate_irradiance(light, {0, 0, 0}, {0, -1, 0}, 64).mean, 0.0);
}

TEST(SphereLight, SnydersFormulaIsContinuousAndMatchesTheVisibleCase) {
  // The formula itself (guards the reference): continuous at the horizon-touching angle, 0 when
  // the sphere has just set.
  const double s2 = 0.09, sigma = std::asin(0.3);
  EXPECT_NEAR(snyder_irradiance(std::cos(kPi / 2 - sigma + 1e-9), s2),
              kPi * s2 * std::cos(kPi / 2 - sigma), 1e-7);
  EXPECT_NEAR(snyder_irradiance(std::cos(kPi / 2 + sigma - 1e-9), s2), 0.0, 1e-7);
}

TEST(SphereLight, SamplesAreOnTheVisibleCapAndUniformInSolidAngle) {
  const SphereLight light = light_at({1, 2, 3}, 0.5f, 1.0f);
  const Vec3 p{0.2f, -0.4f, 0.1f};
  const Vec3 to_c = light.center - p;
  const float d = length(to_c);
  const double cos_max = std::sqrt(1.0 - 0.25 / (double(d) * d));
  const sampling::PixelSampler sampler(0, 0);
  // Chi-square over 8 rings of equal solid angle x 8 sectors (4096 samples, 64 per cell).
  std::vector<int> cells(64, 0);
  const Vec3 a = normalize(to_c);
  const Vec3 e1 = normalize(cross(a, Vec3{0, 0, 1})), e2 = cross(a, e1);
  for (std::uint32_t i = 0; i < 4096; ++i) {
    SphereLightSample s;
    ASSERT_TRUE(sample_sphere_light(light, p, sampler.get_2d(i, 4), s));
    EXPECT_NEAR(length(s.wi), 1.0f, 1e-6f);
    EXPECT_NEAR(length(p + s.wi * s.distance - light.center), light.radius, 2e-6f * d);
    EXPECT_FLOAT_EQ(s.pdf, float(1.0 / (2 * kPi * (1 - cos_max))));
    const double c = std::min(1.0, double(dot(s.wi, a)));
    ASSERT_GE(c, cos_max - 1e-6);
    const int ring = std::min(7, int((1.0 - c) / (1.0 - cos_max) * 8));
    const double phi = std::atan2(double(dot(s.wi, e2)), double(dot(s.wi, e1))) + kPi;
    const int sector = std::min(7, int(phi / (2 * kPi) * 8));
    ++cells[static_cast<std::size_t>(ring * 8 + sector)];
  }
  EXPECT_LT(test::chi_square_uniform(cells, 64.0), test::chi_square_critical_1e6(63));
}

TEST(SphereLight, FalloffNoneScalesBySquaredDistanceToTheCentre) {
  // falloff = "none": E = I cos(theta), whatever the distance (POV-Ray's point light).
  const SphereLight light = light_at({0, 7, 0}, 0.2f, 2.0f, false);
  const Estimate e = estimate_irradiance(light, {0, 0, 0}, {0, 1, 0}, 256);
  EXPECT_NEAR(e.mean, 2.0, 5 * e.standard_error + 1e-5);
}

TEST(SphereLight, PointsInsideTheSphereGetNoSample) {
  const SphereLight light = light_at({0, 0, 0}, 1.0f, 1.0f);
  SphereLightSample s;
  EXPECT_FALSE(sample_sphere_light(light, {0.5f, 0, 0}, {0.3f, 0.7f}, s));
  EXPECT_FALSE(sample_sphere_light(light, {1.0f, 0, 0}, {0.3f, 0.7f}, s));
}

/// Fraction of the cone of half-angle alpha (uniform in solid angle) on the positive side of a
/// plane through the apex whose normal makes angle pi/2 - beta with the axis, i.e. a plane at
/// angular distance beta from the axis: integrated ring by ring (midpoint rule, 4000 rings;
/// error < 1e-6).
double visible_cone_fraction(double alpha, double beta) {
  const int rings = 4000;
  double visible = 0, total = 0;
  for (int k = 0; k < rings; ++k) {
    const double th = (k + 0.5) * alpha / rings, w = std::sin(th);
    // dot(w, m) = cos th sin beta + sin th cos beta cos phi > 0  <=>  cos phi > -tan b / tan th
    const double c = -std::tan(beta) / std::tan(th);
    const double f = c <= -1 ? 1.0 : (c >= 1 ? 0.0 : std::acos(c) / kPi);
    visible += w * f;
    total += w;
  }
  return visible / total;
}

TEST(SphereLight, PenumbraBehindAnEdgeMatchesGeometry) {
  // A sphere light (centre (-a, H, 0), radius R) over an opaque block whose edge runs along z
  // through (0, h): a floor point (x, 0, 0) sees the whole light when the plane through it and
  // the edge passes the centre at distance >= R on the open side, none at >= R on the other.
  // Those two tangent planes bound the penumbra; inside it the visible fraction is the cone's
  // part beyond the plane (visible_cone_fraction). Occlusion by the real scene (BVH, box).
  const double a = 2.0, H = 4.0, R = 0.6, h = 1.0;
  SceneDescription d;
  d.camera.position = {0, 2, 10};
  d.camera.look_at = {0, 0, 0};
  MaterialDescription m;
  m.name = "black";
  d.materials.push_back(m);
  ObjectDescription block;
  block.shape = ObjectDescription::Shape::box;
  block.box_min = {-20, -1, -20};
  block.box_max = {0, h, 20};
  block.material = "black";
  d.objects.push_back(block);
  const Scene scene = build_scene(d);
  const SphereLight light = light_at({float(-a), float(H), 0}, float(R), 1.0f);

  // Signed distance from the centre to the plane through (x, 0, 0) and the edge, positive on the
  // lit side (the plane's in-plane normal (h, x) / |.|, oriented by the far-lit point x = 100).
  auto signed_distance = [&](double x) {
    const double nx = h, ny = x, len = std::hypot(nx, ny);
    return ((-a - 0.0) * nx + (H - h) * ny) / len;
  };
  ASSERT_GT(signed_distance(100.0), R);
  auto solve = [&](double target) {  // bisection for signed_distance(x) = target on [-20, 100]
    double lo = -20, hi = 100;
    for (int i = 0; i < 200; ++i)
      (signed_distance(0.5 * (lo + hi)) < target ? lo : hi) = 0.5 * (lo + hi);
    return 0.5 * (lo + hi);
  };
  const double x_umbra = solve(-R), x_lit = solve(R);
  ASSERT_LT(x_umbra, x_lit);

  const int n = 1024;
  // Tolerance on a visible fraction f inside the penumbra: scrambled (0,m,2)-nets have variance
  // at most 2 f (1 - f) / n (Owen 1997, b/(b-1) = 2 for s = 2), so 5 standard deviations of
  // sqrt(2 * 0.25 / n).
  const double tolerance = 5.0 * std::sqrt(0.5 / n);
  const sampling::PixelSampler sampler(7, 7);
  const double span = x_lit - x_umbra;
  for (int k = -19; k <= 40; ++k) {  // x > 0: never inside the block
    const double x = x_umbra + span * k / 20.0;
    const Vec3 p{float(x), 0.0f, 0.0f};
    int visible = 0;
    for (int i = 0; i < n; ++i) {
      SphereLightSample s;
      ASSERT_TRUE(
          sample_sphere_light(light, p, sampler.get_2d(static_cast<std::uint32_t>(i), 1), s));
      if (!scene.occluded(Ray{p, s.wi, s.distance * (1.0f - 1e-4f)})) ++visible;
    }
    const double f = double(visible) / n;
    if (k < 0) {
      EXPECT_EQ(visible, 0) << "umbra, x = " << x;
    }
    if (k > 20) {
      EXPECT_EQ(visible, n) << "fully lit, x = " << x;
    }
    if (k >= 0 && k <= 20) {
      const Vec3 to_c = light.center - p;
      const double dist = length(to_c);
      const double alpha = std::asin(R / dist),
                   beta = std::asin(std::clamp(signed_distance(x) / dist, -1.0, 1.0));
      EXPECT_NEAR(f, visible_cone_fraction(alpha, beta), tolerance) << "penumbra, x = " << x;
    }
  }
}

}  // namespace
}  // namespace thaw::render
