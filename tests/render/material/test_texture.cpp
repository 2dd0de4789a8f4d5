// Tests render/material/texture.h: the 3D checker parity and offset convention of POV-Ray, its
// libm-free floor.
#include "render/material/texture.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

namespace thaw::render {
namespace {

TEST(Texture, CheckerParityAndOffset) {
  Texture t;
  t.kind = Texture::Kind::checker;
  t.color0 = Rgb{1, 0, 0};
  t.color1 = Rgb{0, 0, 1};
  t.size = 0.5f;
  t.offset = Vec3{0, 0.25f, 0};
  // floor(x/0.5) + floor((y-0.25)/0.5) + floor(z/0.5): (0.1, -1, 0.1) -> 0 - 3 + 0 = -3, odd.
  EXPECT_EQ(t.eval({0.1f, -1.0f, 0.1f}), t.color1);
  EXPECT_EQ(t.eval({0.6f, -1.0f, 0.1f}), t.color0);
  EXPECT_EQ(t.eval({-0.1f, -1.0f, 0.1f}), t.color0);
  t.kind = Texture::Kind::solid;
  EXPECT_EQ(t.eval({0.1f, -1.0f, 0.1f}), t.color0);
}

TEST(Texture, FloorToIntegerIsStdFloor) {
  // The checker's floor without libm must agree with std::floor for every float it can meet:
  // integers, halves, values next to integers on both sides, negatives, tiny and huge (2^24 up,
  // where every float is an integer) magnitudes, and a sweep of bit patterns.
  std::vector<float> v = {0.0f,    -0.0f,       0.5f,         -0.5f, 1.0f,   -1.0f,   1e-30f,
                          -1e-30f, 16777216.0f, -16777217.0f, 3e17f, -3e17f, 4.5e18f, -4.5e18f};
  for (float x = -40.0f; x <= 40.0f; x += 1.0f)
    for (float y : {x, std::nextafter(x, -1e9f), std::nextafter(x, 1e9f)}) v.push_back(y);
  for (std::uint32_t bits = 0; bits < 0x5e000000u; bits += 0x00012345u)  // |v| < 2^61
    for (std::uint32_t sign : {0u, 0x80000000u}) v.push_back(std::bit_cast<float>(bits | sign));
  for (const float x : v)
    ASSERT_EQ(Texture::floor_to_integer(x), static_cast<long long>(std::floor(x))) << x;
}

TEST(Texture, SquareWaveMeanIsTheBoxAverage) {
  // Against a midpoint sum of s(t) = (-1)^floor(t) over [t - h, t + h] with 200000 cells: each
  // cell that straddles a jump is off by at most its width, at most 2h + 1 jumps lie inside, so
  // the sum's error is below (2h + 2) / 200000 of the mean's scale 1/(2h) * 2h: 1e-4 here.
  for (const double t : {0.0, 0.3, 1.7, -2.25, 13.9}) {
    for (const double h : {0.01, 0.4, 1.0, 2.6, 7.3}) {
      constexpr int kCells = 200000;
      double sum = 0;
      for (int i = 0; i < kCells; ++i) {
        const double u = t - h + (i + 0.5) * (2 * h / kCells);
        sum += (static_cast<long long>(std::floor(u)) & 1) == 0 ? 1.0 : -1.0;
      }
      EXPECT_NEAR(Texture::square_wave_mean(t, h), sum / kCells, 1e-4) << t << " " << h;
    }
  }
  EXPECT_EQ(Texture::square_wave_mean(0.5, 0.0), 1.0);
  EXPECT_EQ(Texture::square_wave_mean(1.5, 0.0), -1.0);
}

TEST(Texture, FilteredCheckerTendsToThePointValueAndToTheMean) {
  Texture t;
  t.kind = Texture::Kind::checker;
  t.color0 = Rgb{1, 0, 0};
  t.color1 = Rgb{0, 0, 1};
  t.size = 0.5f;
  // No footprint: the point value.
  EXPECT_EQ(t.eval_filtered({0.1f, 0.2f, 0.3f}, {0, 0, 0}), t.eval({0.1f, 0.2f, 0.3f}));
  // A footprint inside one cell: still that cell's colour exactly.
  const Rgb inside = t.eval_filtered({0.25f, 0.25f, 0.25f}, {0.1f, 0.1f, 0.0f});
  EXPECT_FLOAT_EQ(inside.r, 1.0f);
  EXPECT_FLOAT_EQ(inside.b, 0.0f);
  // A footprint of many cells along x (a grazing view): |mean of s over 2h| <= 1/h [cells], so
  // the colour is within 1/(2h) of the cells' mean (0.5, 0, 0.5); h = 100 cells here.
  const Rgb far = t.eval_filtered({0.1f, 0.2f, 0.3f}, {50.0f, 0.0f, 0.0f});
  EXPECT_NEAR(far.r, 0.5f, 0.005f);
  EXPECT_NEAR(far.b, 0.5f, 0.005f);
  // Symmetric about a cell edge: half and half.
  const Rgb edge = t.eval_filtered({0.5f, 0.2f, 0.3f}, {0.1f, 0.0f, 0.0f});
  EXPECT_NEAR(edge.r, 0.5f, 1e-5f);
}

}  // namespace
}  // namespace thaw::render
