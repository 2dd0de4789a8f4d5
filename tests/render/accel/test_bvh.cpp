// Tests render/accel/bvh.h: closest and any hit agree with brute force on 10^5 random rays over
// random and degenerate triangle sets; rays aimed at shared edges and vertices of a closed mesh
// never miss it (watertight test + conservative slab test together).
#include "render/accel/bvh.h"

#include <gtest/gtest.h>

#include <random>

#include "render/geometry/triangle.h"
#include "tests/render/test_util.h"

namespace thaw::render {
namespace {

struct Tri {
  Vec3 a, b, c;
};

struct Accel {
  Bvh bvh;
  std::vector<Tri> tris;  // in BVH order
  explicit Accel(const std::vector<Tri>& input) {
    std::vector<Aabb> boxes;
    for (const auto& t : input) {
      Aabb b;
      b.extend(t.a);
      b.extend(t.b);
      b.extend(t.c);
      boxes.push_back(b);
    }
    bvh = Bvh(boxes, BvhBuildOptions{4, 1.0f, 64});  // low threshold: exercise the parallel build
    for (auto i : bvh.order()) tris.push_back(input[i]);
  }
  bool closest(const Ray& r, float& t_out) const {
    float t_max = r.t_max;
    const ShearedRay sr(r);
    const bool hit =
        bvh.intersect(Bvh::RayData(r), t_max, [&](std::uint32_t first, std::uint32_t n, float& tm) {
          bool any = false;
          for (std::uint32_t i = first; i < first + n; ++i) {
            TriangleHit h;
            if (intersect_triangle(sr, tris[i].a, tris[i].b, tris[i].c, tm, h)) {
              tm = h.t;
              any = true;
            }
          }
          return any;
        });
    t_out = t_max;
    return hit;
  }
  bool occluded(const Ray& r) const {
    const ShearedRay sr(r);
    return bvh.occluded(Bvh::RayData(r), r.t_max,
                        [&](std::uint32_t first, std::uint32_t n, float tm) {
                          for (std::uint32_t i = first; i < first + n; ++i) {
                            TriangleHit h;
                            if (intersect_triangle(sr, tris[i].a, tris[i].b, tris[i].c, tm, h))
                              return true;
                          }
                          return false;
                        });
  }
};

bool brute_force(const std::vector<Tri>& tris, const Ray& r, float& t_out) {
  const ShearedRay sr(r);
  float t_max = r.t_max;
  bool hit = false;
  for (const auto& t : tris) {
    TriangleHit h;
    if (intersect_triangle(sr, t.a, t.b, t.c, t_max, h)) {
      t_max = h.t;
      hit = true;
    }
  }
  t_out = t_max;
  return hit;
}

void compare_with_brute_force(const std::vector<Tri>& tris, std::uint32_t seed,
                              int n_rays = 100000) {
  const Accel accel(tris);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.5f, 1.5f);
  int mismatches = 0, hits = 0;
  for (int i = 0; i < n_rays; ++i) {
    Ray r{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
    if (length(r.direction) < 1e-3f) continue;
    if (i % 3 == 0) r.t_max = std::abs(u(rng));  // also bounded rays
    float tb = 0, tf = 0;
    const bool hb = accel.closest(r, tb);
    const bool hf = brute_force(tris, r, tf);
    // Same float test on the same triangles: the closest t must agree exactly.
    if (hb != hf || (hb && tb != tf)) ++mismatches;
    if (accel.occluded(r) != hf) ++mismatches;
    hits += hf;
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(hits, n_rays / 100);  // the test means something only if rays do hit
}

TEST(Bvh, RandomTriangleSoupMatchesBruteForce) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), s(-0.15f, 0.15f);
  std::vector<Tri> tris;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 c{u(rng), u(rng), u(rng)};
    tris.push_back({c + Vec3{s(rng), s(rng), s(rng)}, c + Vec3{s(rng), s(rng), s(rng)},
                    c + Vec3{s(rng), s(rng), s(rng)}});
  }
  compare_with_brute_force(tris, 2);
}

TEST(Bvh, IdenticalTrianglesMatchBruteForce) {
  std::vector<Tri> tris(256, Tri{{-1, -1, 0}, {1, -1, 0.2f}, {0, 1, -0.2f}});
  compare_with_brute_force(tris, 3);
}

TEST(Bvh, SameCentroidTrianglesMatchBruteForce) {
  // All centroids at the origin: the SAH has nothing to bin, the median fallback must cope.
  std::vector<Tri> tris;
  for (int i = 0; i < 256; ++i) {
    const float a = 0.0245f * i;
    const Vec3 p{std::cos(a), std::sin(a), 0.01f * (i % 7)}, q{-std::sin(a), std::cos(a), -0.02f};
    tris.push_back({p, q, -(p + q)});
  }
  compare_with_brute_force(tris, 4);
}

TEST(Bvh, ZeroAreaAndCoplanarTrianglesMatchBruteForce) {
  std::vector<Tri> tris;
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) {
      const float x = -1 + i / 8.0f, z = -1 + j / 8.0f;
      if ((i + j) % 5 == 0)
        tris.push_back({{x, 0, z}, {x + 0.1f, 0, z}, {x + 0.2f, 0, z}});  // collinear: zero area
      else
        tris.push_back({{x, 0, z}, {x + 0.125f, 0, z}, {x, 0, z + 0.125f}});  // coplanar grid
    }
  compare_with_brute_force(tris, 5);
}

// Region query: any_leaf with a box test "contains the point q" and a leaf test "a primitive's
// box contains q" finds such a primitive exactly when one exists (brute force), for 2000 points
// over 3000 random boxes; boxes failing the test are never handed to the leaf test whole.
TEST(Bvh, AnyLeafRegionQueryMatchesBruteForce) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Aabb> boxes;
  for (int i = 0; i < 3000; ++i) {
    Aabb b;
    const Vec3 c{10 * u(rng), 10 * u(rng), 10 * u(rng)};
    b.extend(c);
    b.extend(c + Vec3{0.6f * u(rng), 0.6f * u(rng), 0.6f * u(rng)});
    boxes.push_back(b);
  }
  const Bvh bvh(boxes, BvhBuildOptions{4, 1.0f, 4});
  std::vector<Aabb> ordered;
  for (auto i : bvh.order()) ordered.push_back(boxes[i]);
  auto inside = [](const Vec3& q, const Vec3& lo, const Vec3& hi) {
    return q.x >= lo.x && q.y >= lo.y && q.z >= lo.z && q.x <= hi.x && q.y <= hi.y && q.z <= hi.z;
  };
  int found = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 q{10 * u(rng), 10 * u(rng), 10 * u(rng)};
    bool want = false;
    for (const Aabb& b : boxes) want = want || inside(q, b.lo, b.hi);
    const bool got = bvh.any_leaf([&](const Vec3& lo, const Vec3& hi) { return inside(q, lo, hi); },
                                  [&](std::uint32_t first, std::uint32_t count) {
                                    for (std::uint32_t i = first; i < first + count; ++i)
                                      if (inside(q, ordered[i].lo, ordered[i].hi)) return true;
                                    return false;
                                  });
    ASSERT_EQ(got, want) << k;
    found += got;
  }
  EXPECT_GT(found, 50);  // both outcomes occur (boxes fill ~8 % of the volume)
  EXPECT_LT(found, 1980);
  EXPECT_FALSE(Bvh().any_leaf([](const Vec3&, const Vec3&) { return true; },
                              [](std::uint32_t, std::uint32_t) { return true; }));
}

TEST(Bvh, EmptyAndSinglePrimitive) {
  const Bvh empty(std::vector<Aabb>{});
  float t = 1;
  EXPECT_FALSE(empty.intersect(Bvh::RayData(Ray{{0, 0, 0}, {1, 0, 0}}), t,
                               [](auto, auto, float&) { return true; }));
  compare_with_brute_force({Tri{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}}, 6, 10000);
}

TEST(Bvh, ClosedMeshIsWatertightAtEdgesAndVertices) {
  // Rays from inside a closed icosphere aimed exactly at its vertices and edge midpoints (where
  // two or more triangles meet), and from outside through them towards the centre: all must hit.
  const TriangleMesh mesh = test::icosphere(4, 1.0f, {0.1f, -0.2f, 0.3f});
  std::vector<Tri> tris;
  for (const auto& t : mesh.triangles)
    tris.push_back({mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]});
  const Accel accel(tris);
  std::vector<Vec3> targets = mesh.positions;
  for (const auto& t : mesh.triangles)
    for (int e = 0; e < 3; ++e)
      targets.push_back((mesh.positions[t[e]] + mesh.positions[t[(e + 1) % 3]]) * 0.5f);
  const Vec3 inside_points[] = {{0.1f, -0.2f, 0.3f}, {0.35f, 0.1f, 0.2f}, {-0.4f, -0.3f, 0.5f}};
  int misses = 0;
  for (const Vec3& o : inside_points)
    for (const Vec3& target : targets) {
      float t;
      if (!accel.closest(Ray{o, target - o}, t)) ++misses;
      const Vec3 outside = o + (target - o) * 3.0f;
      if (!accel.closest(Ray{outside, o - outside}, t)) ++misses;
    }
  EXPECT_EQ(misses, 0);
}

}  // namespace
}  // namespace thaw::render
