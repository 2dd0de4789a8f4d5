// The density estimate: exact for a uniform photon density, rejects other surfaces.
#include "render/photon/photon_map.h"

#include <gtest/gtest.h>

#include <bit>

#include <cmath>

namespace thaw::render::photon {
namespace {

/// Photons on a square lattice of spacing h over [-a, a]^2 in the plane y = 0, each carrying
/// flux F h^2 (a uniform flux density F per area).
std::vector<Photon> lattice(float h, float a, float flux_density, Vec3 normal = {0, 1, 0}) {
  std::vector<Photon> photons;
  const int n = static_cast<int>(std::lround(a / h));
  for (int i = -n; i <= n; ++i)
    for (int k = -n; k <= n; ++k)
      photons.push_back({Vec3{float(i) * h, 0.0f, float(k) * h}, normal,
                         Rgb{flux_density * h * h, 2 * flux_density * h * h, 0.0f}});
  return photons;
}

// The kernel integrates to 1, so a uniform density F returns F. The lattice sum of the
// Epanechnikov kernel (continuous, a kink at the rim) differs from its integral by O((h/r)^2)
// (the rim's discontinuous derivative; Euler-Maclaurin in 2D): with r = 20 h that is 2.5e-3.
TEST(PhotonMap, UniformDensityGivesExactIrradiance) {
  const float h = 0.01f, r = 0.2f, f = 3.0f;
  const PhotonMap map(lattice(h, 1.0f, f), r, 32.0);
  for (const Vec3 p :
       {Vec3{0, 0, 0}, Vec3{0.1234f, 0, -0.321f}, Vec3{0.005f, 0, 0.005f}, Vec3{-0.5f, 0, 0.37f}}) {
    const Rgb e = map.irradiance(p, {0, 1, 0});
    EXPECT_NEAR(e.r, f, 2.5e-3 * f) << p.x << " " << p.z;
    EXPECT_NEAR(e.g, 2 * f, 2.5e-3 * 2 * f);
    EXPECT_EQ(e.b, 0.0f);
  }
  // Beyond the photons' extent (grown by r): nothing.
  EXPECT_EQ(map.irradiance({3, 0, 0}, {0, 1, 0}).r, 0.0f);
}

// Photons of the other side of the plane (a thin wall lit from below), of a perpendicular wall,
// or off the tangent plane by more than r/4 do not count.
TEST(PhotonMap, RejectsPhotonsOfOtherSurfaces) {
  const float h = 0.01f, r = 0.2f;
  EXPECT_EQ(
      PhotonMap(lattice(h, 1.0f, 1.0f, {0, -1, 0}), r, 32.0).irradiance({0, 0, 0}, {0, 1, 0}).r,
      0.0f);
  // A wall x = 0 (normal +x) next to a floor query at the wall's foot: only the floor counts.
  std::vector<Photon> wall;
  for (int i = 0; i < 40; ++i)
    for (int k = -40; k <= 40; ++k)
      wall.push_back({Vec3{0, float(i) * h, float(k) * h}, Vec3{1, 0, 0}, Rgb{1, 1, 1}});
  EXPECT_EQ(PhotonMap(wall, r, 32.0).irradiance({0.01f, 0, 0}, {0, 1, 0}).r, 0.0f);
  std::vector<Photon> above = lattice(h, 1.0f, 1.0f);
  for (auto& p : above) p.position.y = 0.3f * r;
  EXPECT_EQ(PhotonMap(above, r, 32.0).irradiance({0, 0, 0}, {0, 1, 0}).r, 0.0f);
}

// Sparse photons get wider kernels: a photon with n photons in the 8 grid cells (2r wide)
// around it gets r sqrt(32 / (n pi / 16)), clamped to [r, 8r]. Every kernel integrates to 1, so
// the power is kept: integrating E over the plane returns the photons' power (midpoint rule on a
// grid of r / 8 cells over kernels 8 r wide: 1e-3).
TEST(PhotonMap, SparsePhotonsAreSpreadAndKeepTheirPower) {
  const float r = 0.1f;
  // A lone photon (n = 1) and a pair in one cell (n = 2): both reach 8 r.
  std::vector<Photon> photons{{Vec3{0, 0, 0}, Vec3{0, 1, 0}, Rgb{1, 1, 1}},
                              {Vec3{5, 0, 0}, Vec3{0, 1, 0}, Rgb{1, 1, 1}},
                              {Vec3{5.05f, 0, 0}, Vec3{0, 1, 0}, Rgb{1, 1, 1}}};
  const PhotonMap map(photons, r, 32.0);
  // (The pilot count is hashed: a cell may share its bucket with another's photon, n = 3, which
  // still gives a radius above 2^(5/2) r.)
  ASSERT_EQ(map.photons().size(), 3u);
  for (const Photon& p : map.photons()) {
    EXPECT_LE(p.inv_radius2, 1.0001f / (32 * r * r));
    EXPECT_GE(p.inv_radius2, 0.9999f / (64 * r * r));
  }
  const double lone = 8 * r;
  EXPECT_NEAR(map.irradiance({0, 0, 0}, {0, 1, 0}).g, 2 / (M_PI * lone * lone), 1e-4);
  double total = 0;
  const float h = r / 8;
  for (int i = -80; i <= 120 * 5; ++i)
    for (int k = -80; k <= 80; ++k)
      total +=
          map.irradiance({(float(i) + 0.5f) * h, 0, (float(k) + 0.5f) * h}, {0, 1, 0}).g * h * h;
  EXPECT_NEAR(total, 3.0, 3e-3);
}

// In a uniform density (a lattice of spacing h, cells of 2r = 40 h hold 1600 photons) every
// photon keeps r.
TEST(PhotonMap, DenseRegionsKeepTheBaseRadius) {
  const PhotonMap map(lattice(0.01f, 1.0f, 1.0f), 0.2f, 32.0);
  for (const Photon& p : map.photons()) ASSERT_FLOAT_EQ(p.inv_radius2, 1.0f / (0.2f * 0.2f));
}

// The tree lookup finds every photon whose kernel reaches the query: the same sum as a brute-force
// loop over all photons with the documented rules (kernel, normal within acos 0.9, tangent plane
// within r_p / 4), on clustered and sparse photons of many radii on a floor and a tilted wall.
// Only the order of the float sums differs: relative 1e-5 (a few hundred terms of float
// rounding, 6e-8 each).
TEST(PhotonMap, TreeLookupEqualsBruteForce) {
  std::vector<Photon> photons;
  std::uint32_t s = 12345;
  const auto next = [&s] {
    s = s * 1664525u + 1013904223u;
    return float(s >> 8) / float(1u << 24);
  };
  const Vec3 wall_normal = normalize(Vec3{1, 0.3f, 0});
  for (int i = 0; i < 6000; ++i) {
    // Half in a dense spot, half spread out: radii from r to 8r.
    const float spread = i % 2 ? 0.05f : 1.0f;
    const Vec3 q{(next() - 0.5f) * spread, 0, (next() - 0.5f) * spread};
    if (i % 5 == 0)
      photons.push_back({Vec3{q.x, std::abs(q.z), q.z} + wall_normal * 0.001f, wall_normal,
                         Rgb{next(), next(), 1}});
    else
      photons.push_back({q, Vec3{0, 1, 0}, Rgb{next(), next(), 1}});
  }
  const PhotonMap map(photons, 0.01f, 32.0);
  ASSERT_EQ(map.size(), photons.size());
  for (int k = 0; k < 300; ++k) {
    const Vec3 p{(next() - 0.5f) * (k % 2 ? 0.07f : 1.2f), (next() - 0.5f) * 0.004f,
                 (next() - 0.5f) * (k % 2 ? 0.07f : 1.2f)};
    const Vec3 n = k % 3 ? Vec3{0, 1, 0} : wall_normal;
    double want = 0;
    for (const Photon& ph : map.photons()) {
      const Vec3 v = ph.position - p;
      const double u = double(dot(v, v)) * ph.inv_radius2, h = dot(v, n);
      if (u < 1 && dot(ph.normal, n) >= 0.9f && h * h * ph.inv_radius2 <= 0.0625)
        want += ph.power.r * (1 - u) * ph.inv_radius2 * 2 / M_PI;
    }
    EXPECT_NEAR(map.irradiance_at(SimdLevel::sse2, p, n).r, want, 1e-5 * want + 1e-9) << k;
    if (cpu_supports_avx2()) {
      EXPECT_NEAR(map.irradiance_at(SimdLevel::avx2, p, n).r, want, 1e-5 * want + 1e-9) << k;
    }
  }
}

// The AVX2 leaf kernel against the SSE one (two halves of the same operations, the lanes summed
// in the same order): the same bits for every channel, on the map of the test above's kind
// (two surfaces, radii r to 8r, partly filled last block) and 3000 queries on and off the
// photons' surfaces. Skipped where the CPU has no AVX2.
TEST(PhotonMap, Avx2LookupEqualsSseBitForBit) {
  if (!cpu_supports_avx2()) GTEST_SKIP() << "no AVX2 on this CPU";
  std::vector<Photon> photons;
  std::uint32_t s = 777;
  const auto next = [&s] {
    s = s * 1664525u + 1013904223u;
    return float(s >> 8) / float(1u << 24);
  };
  const Vec3 wall_normal = normalize(Vec3{1, 0.3f, 0});
  for (int i = 0; i < 5003; ++i) {
    const float spread = i % 2 ? 0.05f : 1.0f;
    const Vec3 q{(next() - 0.5f) * spread, 0, (next() - 0.5f) * spread};
    if (i % 5 == 0)
      photons.push_back({Vec3{q.x, std::abs(q.z), q.z} + wall_normal * 0.001f, wall_normal,
                         Rgb{next(), next(), next()}});
    else
      photons.push_back({q, Vec3{0, 1, 0}, Rgb{next(), next(), next()}});
  }
  const PhotonMap map(photons, 0.01f, 32.0);
  int lit = 0;
  for (int k = 0; k < 3000; ++k) {
    const Vec3 p{(next() - 0.5f) * (k % 2 ? 0.07f : 1.2f), (next() - 0.5f) * 0.004f,
                 (next() - 0.5f) * (k % 2 ? 0.07f : 1.2f)};
    const Vec3 n = k % 3 ? Vec3{0, 1, 0} : (k % 2 ? wall_normal : normalize(Vec3{0.3f, 1, 0}));
    const Rgb a = map.irradiance_at(SimdLevel::sse2, p, n),
              b = map.irradiance_at(SimdLevel::avx2, p, n);
    ASSERT_EQ(std::bit_cast<std::uint32_t>(a.r), std::bit_cast<std::uint32_t>(b.r)) << k;
    ASSERT_EQ(std::bit_cast<std::uint32_t>(a.g), std::bit_cast<std::uint32_t>(b.g)) << k;
    ASSERT_EQ(std::bit_cast<std::uint32_t>(a.b), std::bit_cast<std::uint32_t>(b.b)) << k;
    lit += a.g > 0.0f;
  }
  EXPECT_GT(lit, 1000);  // most queries sum photons: the comparison means something
}

// Subtrees on one surface skip the normal and plane tests (photon_map.h): the sum must still be
// the per-photon rule's, also for queries just inside and just outside the tangent-plane limit
// r / 4 (where the shortcut must not be taken), tilted query normals (cos 0.95 and 0.85 against
// the photons' normal) and photons of two normals mixed. Brute force as above; same tolerance.
TEST(PhotonMap, SurfaceShortcutMatchesPerPhotonTests) {
  const float r = 0.02f, h = 0.004f;
  std::vector<Photon> photons = lattice(h, 0.3f, 1.0f);
  const Vec3 tilted = normalize(Vec3{0.2f, 1, 0});
  for (int i = 0; i < 400; ++i)
    photons.push_back(
        {Vec3{float(i % 20) * 0.01f, 0, float(i / 20) * 0.01f}, tilted, Rgb{0.5f, 0.5f, 0.5f}});
  const PhotonMap map(photons, r, 32.0);
  const float cos95 = 0.95f, cos85 = 0.85f;
  const Vec3 normals[] = {{0, 1, 0},
                          tilted,
                          {std::sqrt(1 - cos95 * cos95), cos95, 0},
                          {0, cos85, std::sqrt(1 - cos85 * cos85)}};
  for (const Vec3& n : normals)
    for (const float y : {0.0f, 0.1f, 0.2499f, 0.2501f, -0.2499f, 0.5f})
      for (const Vec3 xz : {Vec3{0, 0, 0}, Vec3{0.0517f, 0, 0.0893f}, Vec3{-0.29f, 0, 0.1f}}) {
        const Vec3 p{xz.x, y * r, xz.z};
        double want = 0;
        for (const Photon& ph : map.photons()) {
          const Vec3 v = ph.position - p;
          const double u = double(dot(v, v)) * ph.inv_radius2, hh = dot(v, n);
          if (u < 1 && dot(ph.normal, n) >= 0.9f && hh * hh * ph.inv_radius2 <= 0.0625)
            want += ph.power.r * (1 - u) * ph.inv_radius2 * 2 / M_PI;
        }
        EXPECT_NEAR(map.irradiance(p, n).r, want, 1e-5 * want + 1e-9)
            << n.x << " " << n.y << " " << y << " " << xz.x;
      }
}

// Every leaf block of the lookup tree is full but the last (its lanes are tested together,
// empty ones cost as much as photons), for any count: ceil(n / kLeafPhotons) blocks.
TEST(PhotonMap, LeafBlocksAreFull) {
  for (const int n : {1, 4, 5, 7, 8, 9, 15, 16, 17, 31, 100, 1001}) {
    std::vector<Photon> photons;
    for (int i = 0; i < n; ++i)
      photons.push_back(
          {Vec3{float(i % 7) * 0.013f, 0, float(i) * 0.007f}, Vec3{0, 1, 0}, Rgb{1, 1, 1}});
    const PhotonMap map(photons, 0.01f, 32.0);
    const std::size_t k = PhotonMap::kLeafPhotons;
    EXPECT_EQ(map.leaf_blocks(), (std::size_t(n) + k - 1) / k) << n;
  }
}

TEST(PhotonMap, EmptyMapIsDark) {
  const PhotonMap map({}, 0.1f, 32.0);
  EXPECT_TRUE(map.empty());
  EXPECT_EQ(map.irradiance({0, 0, 0}, {0, 1, 0}).g, 0.0f);
}

}  // namespace
}  // namespace thaw::render::photon
