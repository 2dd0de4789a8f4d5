// Tests render/geometry/sphere.h: roots from outside and inside, tangent rays, precision far away,
// and that choosing the root before dividing answers exactly as taking both roots did.
#include "render/geometry/sphere.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace thaw::render {
namespace {

/// The previous form of intersect_sphere (both roots always divided out, the smaller positive
/// taken): the reference the branch-per-case form must reproduce bit for bit.
bool intersect_sphere_both_roots(const Ray& ray, const Vec3& center, float radius, float t_max,
                                 float& t_hit) {
  const double fx = double(ray.origin.x) - center.x, fy = double(ray.origin.y) - center.y,
               fz = double(ray.origin.z) - center.z;
  const double dx = ray.direction.x, dy = ray.direction.y, dz = ray.direction.z;
  const double a = dx * dx + dy * dy + dz * dz;
  const double beta = -(fx * dx + fy * dy + fz * dz);
  const double inv_a = 1.0 / a;
  const double s = beta * inv_a;
  const double lx = fx + s * dx, ly = fy + s * dy, lz = fz + s * dz;
  const double r2 = double(radius) * radius;
  const double disc = r2 - (lx * lx + ly * ly + lz * lz);
  if (disc < 0.0) return false;
  const double c = fx * fx + fy * fy + fz * fz - r2;
  const double q = beta + std::copysign(std::sqrt(a * disc), beta);
  if (q == 0.0) return false;
  double t0 = c / q, t1 = q * inv_a;
  if (t0 > t1) std::swap(t0, t1);
  const double t = t0 > 0.0 ? t0 : t1;
  if (!(t > 0.0) || !(t < t_max)) return false;
  t_hit = static_cast<float>(t);
  return t_hit > 0.0f && t_hit < t_max;
}

TEST(Sphere, FromOutsideNearRoot) {
  float t;
  ASSERT_TRUE(intersect_sphere(Ray{{0, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1.0f, 1e30f, t));
  EXPECT_FLOAT_EQ(t, 4.0f);
}

TEST(Sphere, FromInsideFarRoot) {
  float t;
  ASSERT_TRUE(intersect_sphere(Ray{{0, 0, 0.5f}, {0, 0, -1}}, {0, 0, 0}, 1.0f, 1e30f, t));
  EXPECT_FLOAT_EQ(t, 1.5f);
}

TEST(Sphere, MissesBehindBesideAndBeyondTMax) {
  float t;
  EXPECT_FALSE(intersect_sphere(Ray{{0, 0, 5}, {0, 0, 1}}, {0, 0, 0}, 1.0f, 1e30f, t));
  EXPECT_FALSE(intersect_sphere(Ray{{1.001f, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1.0f, 1e30f, t));
  EXPECT_FALSE(intersect_sphere(Ray{{0, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1.0f, 3.9f, t));
}

TEST(Sphere, UnnormalisedDirection) {
  float t;
  ASSERT_TRUE(intersect_sphere(Ray{{0, 0, 5}, {0, 0, -2}}, {0, 0, 0}, 1.0f, 1e30f, t));
  EXPECT_FLOAT_EQ(t, 2.0f);
}

TEST(Sphere, SmallSphereFarAwayIsAccurate) {
  // The naive quadratic loses all digits here (b^2 ~ 1e12 vs c ~ 1e12); Haines et al.'s form keeps
  // the hit within float rounding of the distance: |t - 99999| <= 4 ulp(1e5) ~ 0.03.
  float t;
  ASSERT_TRUE(intersect_sphere(Ray{{0, 0, 1e5f}, {0, 0, -1}}, {0, 0, 0}, 1.0f, 1e30f, t));
  EXPECT_NEAR(t, 99999.0f, 0.03f);
}

TEST(Sphere, SameAnswersAsTakingBothRoots) {
  // Rays of every kind a render makes: from far outside towards and away from the sphere, grazing,
  // from inside, and leaving the surface from a point rounded to float (secondary and shadow
  // rays), with unit and unnormalised directions and finite or infinite t_max. Hit or miss and
  // the bits of t must agree for every ray.
  std::mt19937 rng(12345);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(0.0f, 1.0f);
  const float inf = std::numeric_limits<float>::infinity();
  int hits = 0, misses = 0;
  for (int i = 0; i < 400000; ++i) {
    const Vec3 center{4.0f * u(rng), 4.0f * u(rng), 4.0f * u(rng)};
    const float radius = std::exp2(6.0f * u(rng));  // 1/64 .. 64
    Vec3 dir{u(rng), u(rng), u(rng)};
    if (length(dir) < 1e-3f) continue;
    if (i % 3 != 0) dir = normalize(dir);
    Vec3 origin;
    switch (i % 4) {
      case 0:  // anywhere, often outside
        origin = center + Vec3{u(rng), u(rng), u(rng)} * (3.0f * radius);
        break;
      case 1:  // on the surface (rounded to float)
        origin = center + normalize(Vec3{u(rng), u(rng), u(rng)}) * radius;
        break;
      case 2:  // inside
        origin = center + Vec3{u(rng), u(rng), u(rng)} * (0.5f * radius);
        break;
      default:  // aimed at a point near the rim: grazing rays
        origin = center + dir * (-5.0f * radius) +
                 normalize(cross(dir, Vec3{u(rng), u(rng), u(rng)})) *
                     (radius * (1.0f + 1e-3f * u(rng)));
        break;
    }
    const float t_max = i % 5 == 0 ? inf : 8.0f * radius * pos(rng);
    const Ray ray{origin, dir};
    float t_new = -1.0f, t_ref = -1.0f;
    const bool hit_new = intersect_sphere(ray, center, radius, t_max, t_new);
    const bool hit_ref = intersect_sphere_both_roots(ray, center, radius, t_max, t_ref);
    ASSERT_EQ(hit_new, hit_ref) << "ray " << i;
    if (hit_ref) {
      ASSERT_EQ(std::bit_cast<std::uint32_t>(t_new), std::bit_cast<std::uint32_t>(t_ref)) << i;
      ++hits;
    } else {
      ++misses;
    }
  }
  // Both outcomes must be well represented for the comparison to mean something.
  EXPECT_GT(hits, 100000);
  EXPECT_GT(misses, 100000);
}

}  // namespace
}  // namespace thaw::render
