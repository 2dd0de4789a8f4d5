// Tests render/accel/bvh.h: closest and any hit agree with brute force on 10^5 random rays over
// random and degenerate triangle sets, on the SSE and (where the CPU has it) the AVX2 path; rays
// aimed at shared edges and vertices of a closed mesh never miss it (watertight test +
// conservative slab test together); the two paths test the same nodes bit for bit and visit the
// same leaves in the same order (so they return the same hit, ties included).
#include "render/accel/bvh.h"

#include <gtest/gtest.h>

#include <bit>
#include <limits>
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
  /// wide8_min_primitives 0: rays traverse the 8-wide tree; SIZE_MAX: the 4-wide one.
  explicit Accel(const std::vector<Tri>& input, std::size_t wide8_min_primitives = 0) {
    std::vector<Aabb> boxes;
    for (const auto& t : input) {
      Aabb b;
      b.extend(t.a);
      b.extend(t.b);
      b.extend(t.c);
      boxes.push_back(b);
    }
    // A low parallel threshold: exercise the parallel build.
    bvh = Bvh(boxes, BvhBuildOptions{.parallel_threshold = 64,
                                     .wide8_min_primitives = wide8_min_primitives});
    for (auto i : bvh.order()) tris.push_back(input[i]);
  }
  bool closest(const Ray& r, float& t_out, SimdLevel level = simd_level()) const {
    float t_max = r.t_max;
    const ShearedRay sr(r);
    const bool hit = bvh.intersect_at(
        level, Bvh::RayData(r), t_max, [&](std::uint32_t first, std::uint32_t n, float& tm) {
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
  bool occluded(const Ray& r, SimdLevel level = simd_level()) const {
    const ShearedRay sr(r);
    return bvh.occluded_at(level, Bvh::RayData(r), r.t_max,
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

/// The instruction sets this machine can run: always SSE2, and AVX2 where the CPU has it.
std::vector<SimdLevel> levels() {
  std::vector<SimdLevel> l{SimdLevel::sse2};
  if (cpu_supports_avx2()) l.push_back(SimdLevel::avx2);
  return l;
}

void compare_with_brute_force(const std::vector<Tri>& tris, std::uint32_t seed,
                              int n_rays = 100000) {
  struct Case {
    Ray ray;
    bool hit;
    float t;
  };
  std::vector<Case> cases;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.5f, 1.5f);
  int hits = 0;
  for (int i = 0; i < n_rays; ++i) {
    Ray r{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
    if (length(r.direction) < 1e-3f) continue;
    if (i % 3 == 0) r.t_max = std::abs(u(rng));  // also bounded rays
    float t = 0;
    const bool hit = brute_force(tris, r, t);
    cases.push_back({r, hit, t});
    hits += hit;
  }
  EXPECT_GT(hits, n_rays / 100);  // the test means something only if rays do hit
  // Both tree widths, each on every instruction set this machine runs.
  for (const std::size_t wide8_min : {std::size_t(0), std::numeric_limits<std::size_t>::max()}) {
    const Accel accel(tris, wide8_min);
    for (const SimdLevel level : levels()) {
      SCOPED_TRACE(level == SimdLevel::avx2 ? "avx2" : "sse2");
      SCOPED_TRACE(wide8_min == 0 ? "8-wide" : "4-wide");
      int mismatches = 0;
      for (const Case& c : cases) {
        float t = 0;
        const bool hit = accel.closest(c.ray, t, level);
        // Same float test on the same triangles: the closest t must agree exactly.
        if (hit != c.hit || (hit && t != c.t)) ++mismatches;
        if (accel.occluded(c.ray, level) != c.hit) ++mismatches;
      }
      EXPECT_EQ(mismatches, 0);
    }
  }
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
  ASSERT_FALSE(bvh.wide8_nodes().empty());
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
    // The same query over the 8-wide nodes (3000 boxes: the tree has them).
    const auto boxes8 = [&](const float(&planes)[6][8]) {
      unsigned mask = 0;
      for (int i = 0; i < 8; ++i) {
        const Vec3 lo{planes[0][i], planes[2][i], planes[4][i]};
        const Vec3 hi{planes[1][i], planes[3][i], planes[5][i]};
        if (!(lo.x > hi.x) && inside(q, lo, hi)) mask |= 1u << i;
      }
      return mask;
    };
    const bool got8 =
        bvh.any_leaf_wide8(boxes8, boxes8, [&](std::uint32_t first, std::uint32_t count) {
          for (std::uint32_t i = first; i < first + count; ++i)
            if (inside(q, ordered[i].lo, ordered[i].hi)) return true;
          return false;
        });
    ASSERT_EQ(got8, want) << k;
    found += got;
  }
  EXPECT_GT(found, 50);  // both outcomes occur (boxes fill ~8 % of the volume)
  EXPECT_LT(found, 1980);
  EXPECT_FALSE(Bvh().any_leaf([](const Vec3&, const Vec3&) { return true; },
                              [](std::uint32_t, std::uint32_t) { return true; }));
}

// The AVX2 node test against the SSE one on random 8-wide nodes (random, empty, flat and
// point-like boxes, unused slots) and random rays (axis-parallel ones included): the same mask
// and the same entry distances to the bit. Skipped where the CPU has no AVX2.
TEST(Bvh, Avx2NodeTestEqualsSseBitForBit) {
#if THAW_AVX2_DISPATCH
  if (!cpu_supports_avx2()) GTEST_SKIP() << "no AVX2 on this CPU";
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f), e(0.0f, 3.0f);
  int masks_seen = 0;
  for (int k = 0; k < 20000; ++k) {
    Bvh8Node n{};
    for (int i = 0; i < 8; ++i) {
      const int kind = static_cast<int>(rng() % 5);
      for (int a = 0; a < 3; ++a) {
        float lo = u(rng), hi = lo + (kind == 1 ? 0.0f : e(rng));  // kind 1: a point
        if (kind == 2 && a == 1) hi = lo;                          // kind 2: flat
        if (kind == 3) {                                           // kind 3: an unused slot
          lo = std::numeric_limits<float>::infinity();
          hi = -lo;
        }
        n.planes[2 * a][i] = lo;
        n.planes[2 * a + 1][i] = hi;
      }
    }
    Vec3 d{u(rng), u(rng), u(rng)};
    if (k % 7 == 0) d[k % 3] = 0.0f;          // parallel to a slab
    if (k % 11 == 0) d = Vec3{0, u(rng), 0};  // parallel to two slabs
    const Ray ray{{u(rng), u(rng), u(rng)}, d};
    const Bvh::RayData rd(ray);
    const float t_max = k % 3 == 0 ? std::numeric_limits<float>::infinity() : 2.0f * e(rng);
    alignas(32) float ts[8], ta[8];
    const int ms = Bvh::Children8(rd)(n, t_max, ts);
    const int ma = Bvh::Children8Avx2(rd)(n, t_max, ta);
    ASSERT_EQ(ms, ma) << k;
    for (int i = 0; i < 8; ++i) {
      if (ms & (1 << i)) {
        ASSERT_EQ(std::bit_cast<std::uint32_t>(ts[i]), std::bit_cast<std::uint32_t>(ta[i])) << k;
      }
    }
    masks_seen += ms != 0 && ms != 0xff;
  }
  EXPECT_GT(masks_seen, 1000);  // partial masks occur: the comparison means something
#else
  GTEST_SKIP() << "no AVX2 code path in this build";
#endif
}

// Both paths over the S1-like nested shells (two icospheres and a floor) with rays starting on
// their surfaces: the same leaves in the same order, hence the same hit. Skipped without AVX2.
TEST(Bvh, Avx2AndSseVisitTheSameLeavesInTheSameOrder) {
  if (!cpu_supports_avx2()) GTEST_SKIP() << "no AVX2 on this CPU";
  std::vector<Tri> tris;
  for (const TriangleMesh& mesh :
       {test::icosphere(4, 1.0f, {0, 0, 0}), test::icosphere(3, 0.7f, {0.05f, 0, 0})})
    for (const auto& t : mesh.triangles)
      tris.push_back({mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]});
  tris.push_back({{-5, -1, -5}, {5, -1, -5}, {5, -1, 5}});
  tris.push_back({{-5, -1, -5}, {5, -1, 5}, {-5, -1, 5}});
  const Accel accel(tris);
  ASSERT_FALSE(accel.bvh.wide8_nodes().empty());
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), w(0.0f, 1.0f);
  int differing = 0, hits = 0;
  for (int k = 0; k < 20000; ++k) {
    const Tri& on = tris[rng() % tris.size()];
    const float b1 = w(rng), b2 = w(rng) * (1.0f - b1);
    const Vec3 o = on.a * (1.0f - b1 - b2) + on.b * b1 + on.c * b2;  // on a surface
    const Ray ray{o, {u(rng), u(rng), u(rng)}};
    std::vector<std::uint32_t> visits[2];
    float t[2];
    bool hit[2];
    const SimdLevel lv[2] = {SimdLevel::sse2, SimdLevel::avx2};
    for (int p = 0; p < 2; ++p) {
      float t_max = ray.t_max;
      const ShearedRay sr(ray);
      hit[p] = accel.bvh.intersect_at(
          lv[p], Bvh::RayData(ray), t_max, [&](std::uint32_t first, std::uint32_t n, float& tm) {
            visits[p].push_back(first);
            bool any = false;
            for (std::uint32_t i = first; i < first + n; ++i) {
              TriangleHit h;
              if (intersect_triangle(sr, accel.tris[i].a, accel.tris[i].b, accel.tris[i].c, tm,
                                     h)) {
                tm = h.t;
                any = true;
              }
            }
            return any;
          });
      t[p] = t_max;
    }
    if (visits[0] != visits[1] || hit[0] != hit[1] || t[0] != t[1]) ++differing;
    hits += hit[0];
  }
  EXPECT_EQ(differing, 0);
  EXPECT_GT(hits, 10000);
}

TEST(Bvh, EmptyAndSinglePrimitive) {
  const Bvh empty(std::vector<Aabb>{});
  float t = 1;
  EXPECT_FALSE(empty.intersect(Bvh::RayData(Ray{{0, 0, 0}, {1, 0, 0}}), t,
                               [](auto, auto, float&) { return true; }));
  compare_with_brute_force({Tri{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}}}, 6, 10000);
}

// The SAH counts primitives that are tested one by one (spheres) as one test each, and blockable
// ones (triangles) block_size per test: four well-separated unit boxes in a row stay one leaf as
// blockable primitives (one 4-wide test beats a split) and become four leaves when tested alone.
TEST(Bvh, PrimitivesTestedAloneAreNotPackedIntoOneLeaf) {
  std::vector<Aabb> boxes;
  for (int i = 0; i < 4; ++i) {
    Aabb b;
    b.extend(Vec3{3.0f * i, 0, 0});
    b.extend(Vec3{3.0f * i + 1, 1, 1});
    boxes.push_back(b);
  }
  auto leaves = [](const Bvh& bvh) {
    int n = 0;
    for (const BvhNode& node : bvh.nodes()) n += node.count > 0;
    return n;
  };
  EXPECT_EQ(leaves(Bvh(boxes)), 1);
  const std::vector<std::uint8_t> alone(4, 1);
  EXPECT_EQ(leaves(Bvh(boxes, BvhBuildOptions{}, alone)), 4);
  const std::vector<std::uint8_t> mixed{0, 0, 1, 1};  // two blockable, two alone
  EXPECT_GE(leaves(Bvh(boxes, BvhBuildOptions{}, mixed)), 2);
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
