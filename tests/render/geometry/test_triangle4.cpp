// Tests render/geometry/triangle4.h: each lane agrees bit for bit with the scalar test of
// triangle.h, including its t error bound (a ray leaving a large triangle never re-hits it).
#include "render/geometry/triangle4.h"

#include <gtest/gtest.h>

#include "tests/render/geometry/large_triangle_rays.h"

namespace thaw::render {
namespace {

TEST(Triangle4, RayLeavingLargeTriangleNeverReHitsIt) {
  int rehits = 0, total = 0;
  test::for_each_ray_leaving_large_triangle(
      [&](const Ray& r, const Vec3& a, const Vec3& b, const Vec3& c) {
        Triangle4 block{};
        for (int lane = 0; lane < 4; ++lane) block.set(lane, a, b, c, 0);
        TriangleHit h;
        int lane = -1;
        ++total;
        if (intersect_triangle4(ShearedRay(r), block, r.t_max, h, lane)) ++rehits;
        if (intersect_triangle4(ShearedRay(r), block, r.t_max, h, lane, true)) ++rehits;
      });
  EXPECT_GT(total, 10000);
  EXPECT_EQ(rehits, 0);
}

TEST(Triangle4, LanesMatchScalarTestBitForBit) {
  // Rays from above towards a large quad's two triangles and two small ones: hits, misses and
  // near-misses; every lane's t and barycentrics must equal intersect_triangle's exactly.
  const Vec3 v[4][3] = {{{-100, -1, -100}, {-100, -1, 100}, {100, -1, 100}},
                        {{-100, -1, -100}, {100, -1, 100}, {100, -1, -100}},
                        {{0, 0, 0}, {1, 0.2f, 0}, {0, 1, 0.3f}},
                        {{0.5f, -0.5f, -2}, {0.7f, 0.5f, -2}, {-0.3f, 0, -2.5f}}};
  Triangle4 block{};
  for (int lane = 0; lane < 4; ++lane)
    block.set(lane, v[lane][0], v[lane][1], v[lane][2], std::uint32_t(lane));
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 origin{0.01f * float(i % 37) - 0.2f, 3.0f, 0.013f * float(i % 53) - 0.3f};
    const Vec3 dir{0.0007f * float(i % 11) - 0.003f, -1.0f, -0.001f * float(i % 7)};
    const Ray r{origin, dir};
    const ShearedRay sr(r);
    for (int lane = 0; lane < 4; ++lane) {
      Triangle4 one{};
      for (int l = 0; l < 4; ++l)
        one.set(l, v[lane][0], v[lane][1], v[lane][2], std::uint32_t(lane));
      TriangleHit hs{}, h4{};
      int l4 = -1;
      const bool s = intersect_triangle(sr, v[lane][0], v[lane][1], v[lane][2], 1e30f, hs);
      const bool f = intersect_triangle4(sr, one, 1e30f, h4, l4);
      ASSERT_EQ(s, f) << i << " " << lane;
      if (!s) continue;
      ++hits;
      EXPECT_EQ(hs.t, h4.t);
      EXPECT_EQ(hs.b1, h4.b1);
      EXPECT_EQ(hs.b2, h4.b2);
    }
  }
  EXPECT_GT(hits, 1000);
}

}  // namespace
}  // namespace thaw::render
