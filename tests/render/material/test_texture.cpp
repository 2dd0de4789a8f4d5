// Tests render/material/texture.h: the 3D checker parity and offset convention of POV-Ray, its
// libm-free floor, its closed-form box mean against numerical integration, and its footprint
// mean (limits, one exact box along a texture axis, the diagonal frame's closed form and its
// choice).
#include "render/material/texture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

namespace thaw::render {
namespace {

Texture red_blue_checker(float size) {
  Texture t;
  t.kind = Texture::Kind::checker;
  t.color0 = Rgb{1, 0, 0};
  t.color1 = Rgb{0, 0, 1};
  t.size = size;
  return t;
}

/// The point-sampled checker's red channel (1 on colour 0, 0 on colour 1) averaged over the box
/// c +- e, numerically: along x exactly (the row split at every cell boundary, each piece's
/// length times eval() at its middle), along y and z by the midpoint rule on an n x n grid of
/// rows (one row when that extent is 0). Only rows whose cell straddles a jump in y or z are
/// wrong, each by at most 1 in red; at most n (J_y + J_z) of n^2 rows do, with J the jumps inside
/// the box, so the error is at most (J_y + J_z) / n.
double numerical_box_mean(const Texture& t, const Vec3& c, const Vec3& e, int n) {
  const int ny = e.y > 0 ? n : 1, nz = e.z > 0 ? n : 1;
  double sum = 0;
  for (int j = 0; j < ny; ++j) {
    for (int k = 0; k < nz; ++k) {
      const double y = c.y - e.y + (j + 0.5) * 2.0 * e.y / ny;
      const double z = c.z - e.z + (k + 0.5) * 2.0 * e.z / nz;
      const double x0 = c.x - e.x, x1 = c.x + e.x;
      double row = 0;
      for (double a = x0; a < x1;) {
        const double b = std::min(x1, (std::floor(a / t.size + 1e-9) + 1.0) * t.size);
        const Vec3 mid{float(0.5 * (a + b)), float(y), float(z)};
        row += (b - a) * t.eval(mid).r;
        a = b;
      }
      sum += row / (x1 - x0);
    }
  }
  return sum / (double(ny) * nz);
}

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

TEST(Texture, BoxMeanMatchesNumericalIntegration) {
  // eval_filtered (a product of per-axis closed forms) against the point-sampled checker
  // integrated numerically over 2D boxes (a floor: no extent in y) and 3D boxes, off-centre,
  // across negative coordinates, from inside one cell to many cells. Tolerance: the integration's
  // bound (J_y + J_z) / n (numerical_box_mean) with J <= 2 e / size + 1 jumps per axis, plus the
  // float rounding of the colours (1e-6).
  const Texture t = red_blue_checker(0.5f);
  const Vec3 centres[] = {{0.1f, 0.2f, 0.3f}, {-1.37f, 0.7f, 2.05f}, {3.9f, -0.26f, -0.8f}};
  const Vec3 extents[] = {{0.1f, 0.0f, 0.05f}, {0.6f, 0.0f, 0.2f},  {1.3f, 0.0f, 2.7f},
                          {0.35f, 0.0f, 4.0f}, {0.3f, 0.4f, 0.45f}, {1.1f, 0.8f, 0.27f}};
  constexpr int n = 400;
  for (const Vec3& c : centres) {
    for (const Vec3& e : extents) {
      const double jumps = (e.y > 0 ? 2 * e.y / t.size + 1 : 0) + 2 * e.z / t.size + 1;
      const double tolerance = jumps / (e.y > 0 ? n / 4 : n) + 1e-6;
      const double reference = numerical_box_mean(t, c, e, e.y > 0 ? n / 4 : n);
      const Rgb filtered = t.eval_filtered(c, e);
      EXPECT_NEAR(filtered.r, reference, tolerance) << c.x << " " << e.x << " " << e.z;
      EXPECT_NEAR(filtered.r + filtered.b, 1.0, 1e-6);  // weights of the two colours sum to 1
    }
  }
}

TEST(Texture, FootprintLimitsArePointSampleAndMean) {
  const Texture t = red_blue_checker(0.5f);
  const Vec3 x{1, 0, 0}, z{0, 0, 1};
  // No extent, or one far below a cell (1e-7 cells, below float resolution): the point value.
  for (const Vec3 c : {Vec3{0.1f, 0.2f, 0.3f}, Vec3{-0.7f, 0.1f, 0.6f}}) {
    EXPECT_EQ(t.eval_footprint({c, x, z, 0.0f, 0.0f}), t.eval(c));
    EXPECT_EQ(t.eval_footprint({c, x, z, 5e-8f, 5e-8f}), t.eval(c));
  }
  // A footprint of thousands of cells: the mean colour (0.5, 0, 0.5), within the box mean's
  // bound |mean of s over 2h| <= 1/(2h) per axis (h in cells; 2000 and 1000 here: 2.5e-4 for
  // the product of two), for any orientation in the floor's plane.
  const float r = std::sqrt(0.5f);
  for (const Vec3& a : {x, Vec3{r, 0, r}, Vec3{0.6f, 0, -0.8f}}) {
    const Vec3 b = cross(Vec3{0, 1, 0}, a);
    const Rgb far = t.eval_footprint({{0.3f, 0.1f, -0.2f}, a, b, 1000.0f, 500.0f});
    EXPECT_NEAR(far.r, 0.5f, 2.5e-4f);
    EXPECT_NEAR(far.b, 0.5f, 2.5e-4f);
  }
  // Solid textures ignore the footprint.
  Texture solid;
  solid.color0 = Rgb{0.2f, 0.3f, 0.4f};
  EXPECT_EQ(solid.eval_footprint({{0, 0, 0}, x, z, 3.0f, 1.0f}), solid.color0);
}

TEST(Texture, FootprintAlongATextureAxisIsOneExactBox) {
  // An ellipse whose long axis follows x is bounded by the box (major, minor) in x and z: one
  // box, the same value as eval_filtered's, for any elongation.
  const Texture t = red_blue_checker(0.5f);
  for (const float major : {0.2f, 1.3f, 7.0f}) {
    const Vec3 c{0.37f, 0.1f, -0.61f};
    const Rgb f = t.eval_footprint({c, {1, 0, 0}, {0, 0, -1}, major, 0.15f});
    EXPECT_EQ(f, t.eval_filtered(c, {major, 0.0f, 0.15f})) << major;
  }
}

TEST(Texture, DiagonalBoxMeanMatchesNumericalIntegration) {
  // The closed form against the point checker s(u) s(v) (parity of floor u + floor v) over the
  // box in diagonal coordinates, integrated numerically: each of n rows of constant m exactly in
  // p (split where u = (p + m)/2 or v = (p - m)/2 crosses an integer, the parity at each piece's
  // middle), the rows by the midpoint rule. The row integral is piecewise linear in m with slopes
  // of at most 2 (two moving breakpoints per crossing) and jumps of at most 4 at fewer than
  // K = 4 (hm + hp + 2) kinks; the midpoint rule is exact on linear pieces and off by at most
  // 4 dm^2 / 8 at a kink: error <= K dm^2 / 2 / (2 hm) with dm = 2 hm / n, below 1e-4 here.
  const auto point = [](double u, double v) {
    return ((long long)std::floor(u) + (long long)std::floor(v)) % 2 == 0 ? 1.0 : -1.0;
  };
  const int n = 800;
  for (const auto& [p, m, hp, hm] : std::vector<std::array<double, 4>>{{0.3, 0.1, 0.4, 0.2},
                                                                       {1.7, -0.4, 2.5, 0.05},
                                                                       {-3.2, 5.1, 0.7, 1.9},
                                                                       {10.25, 0.0, 3.0, 0.1},
                                                                       {0.0, 0.0, 0.01, 0.01}}) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j) {
      const double mj = m - hm + (j + 0.5) * 2.0 * hm / n;
      std::vector<double> cuts{p - hp, p + hp};
      for (double k = std::floor((p - hp + mj) / 2.0); 2.0 * k - mj < p + hp; ++k)
        cuts.push_back(2.0 * k - mj);  // u = k
      for (double k = std::floor((p - hp - mj) / 2.0); 2.0 * k + mj < p + hp; ++k)
        cuts.push_back(2.0 * k + mj);  // v = k
      std::sort(cuts.begin(), cuts.end());
      double row = 0.0;
      for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
        const double a0 = std::max(cuts[c], p - hp), a1 = std::min(cuts[c + 1], p + hp);
        if (a1 <= a0) continue;
        const double mid = 0.5 * (a0 + a1);
        row += (a1 - a0) * point(0.5 * (mid + mj), 0.5 * (mid - mj));
      }
      sum += row / (2.0 * hp);
    }
    const double kinks = 4.0 * (hm + hp + 2.0), dm = 2.0 * hm / n;
    const double bound = kinks * dm * dm / 2.0 / (2.0 * hm) + 1e-9;
    EXPECT_NEAR(Texture::diagonal_box_mean(p, m, hp, hm), sum / n, bound)
        << p << " " << m << " " << hp << " " << hm;
  }
  // Periodic in p and in m apart (period 2 each), and the point value for a small box inside a
  // cell: p = 1, m = 0 is u = v = 0.5, colour 0.
  EXPECT_NEAR(Texture::diagonal_box_mean(1.0, 0.0, 0.1, 0.1), 1.0, 1e-9);
  EXPECT_NEAR(Texture::diagonal_box_mean(0.0, 1.0, 0.1, 0.1), -1.0, 1e-9);
  EXPECT_NEAR(Texture::diagonal_box_mean(0.37, 0.81, 0.6, 0.3),
              Texture::diagonal_box_mean(4.37, -5.19, 0.6, 0.3), 1e-9);
}

TEST(Texture, DiagonalFootprintKeepsTheDiagonalRowsContrast) {
  // A footprint 100 times longer than wide along the diagonal x = z (a floor seen at 45 degrees
  // to its rows, towards the horizon), centred on the middle of a colour-0 cell: it runs along a
  // chain of colour-0 cells touching corner to corner. In diagonal coordinates (p = x + z,
  // m = x - z) it spans |m| <= sqrt(2) B and colour 1 fills the part |p - even| < |m|: a share of
  // the mean of |m|, B / sqrt(2) = 0.0707 for B = 0.1 cells, up to the partial period of p
  // (0.28 of its 28.3 at most 0.0014). The box of the texture's axes around it (0.7 A = 7 cells in
  // x and z) gave the mean colour, 0.5 red, within 2.5e-3.
  const Texture t = red_blue_checker(1.0f);
  const float r = std::sqrt(0.5f);
  const Vec3 a{r, 0, r}, b{-r, 0, r};
  for (const Vec3 c : {Vec3{0.5f, 0.5f, 0.5f}, Vec3{-3.5f, 0.5f, 4.5f}}) {
    const Rgb f = t.eval_footprint({c, a, b, 10.0f, 0.1f});
    EXPECT_NEAR(f.r, 1.0 - 0.1 / std::sqrt(2.0), 0.003) << c.x;
    EXPECT_NEAR(f.r + f.b, 1.0f, 1e-6f);
  }
  // Across the chains (centred on a corner between them, m = 1) it is the other colour's mean:
  // the rows are resolved across the view and kept.
  const Rgb across = t.eval_footprint({{1.0f, 0.5f, 0.0f}, a, b, 10.0f, 0.1f});
  EXPECT_LT(across.r, 0.1f);
}

TEST(Texture, FootprintFrameIsTheTighterBoxWithoutASeam) {
  // A round footprint, turned any way, and one along a texture axis keep the box of the
  // texture's axes (that box is no larger than the diagonal one); turning an elongated footprint
  // from the x axis to the diagonal moves the value continuously (the two boxes are blended where
  // their areas are within a factor 1/0.7): no step between 0.01-degree turns larger than what the
  // box means' own slope gives (|d mean / d angle| <= 2 (A / cell) / h_min per radian, ~0.02
  // here), where switching boxes at once would jump by up to 1.
  const Texture t = red_blue_checker(1.0f);
  const Vec3 c{0.3f, 0.5f, 0.8f};
  for (const float deg : {0.0f, 17.0f, 45.0f, 60.0f}) {
    const float th = deg * 3.14159265f / 180.0f;
    const Vec3 a{std::cos(th), 0, std::sin(th)}, b{-std::sin(th), 0, std::cos(th)};
    const float e = 0.4f * std::sqrt(std::cos(th) * std::cos(th) + std::sin(th) * std::sin(th));
    EXPECT_NEAR(t.eval_footprint({c, a, b, 0.4f, 0.4f}).r, t.eval_filtered(c, {e, 0, e}).r, 1e-6f)
        << deg;
  }
  float previous = -1.0f, largest_step = 0.0f;
  for (int step = 0; step <= 4500; ++step) {
    const float th = float(step) * 0.01f * 3.14159265f / 180.0f;
    const Vec3 a{std::cos(th), 0, std::sin(th)}, b{-std::sin(th), 0, std::cos(th)};
    const float red = t.eval_footprint({c, a, b, 3.0f, 0.3f}).r;
    if (previous >= 0.0f) largest_step = std::max(largest_step, std::abs(red - previous));
    previous = red;
  }
  EXPECT_LT(largest_step, 0.02f);
}

}  // namespace
}  // namespace thaw::render
