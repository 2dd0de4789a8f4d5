// Tests render/light/irradiance_sh.h: the order-2 spherical-harmonic irradiance is exact for a
// constant radiance (E = pi L) and for a linear one (E = pi a + 2 pi / 3 b.n), and for a sky
// gradient stays within the bound that follows from truncating the clamped cosine at order 2.
#include "render/light/irradiance_sh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace thaw::render {
namespace {

const Vec3 kNormals[] = {{0, 1, 0},  {0, -1, 0},      {1, 0, 0},
                         {0, 0, -1}, {0.6f, 0.8f, 0}, {0.48f, -0.6f, 0.64f}};

TEST(IrradianceSH, ConstantRadianceGivesPiL) {
  const auto sh = IrradianceSH::project([](const Vec3&) { return Rgb{0.5f, 1.0f, 2.0f}; });
  // The weights sum to 4 pi exactly and the grid is symmetric: float rounding only.
  for (const Vec3& n : kNormals) {
    const Rgb e = sh.irradiance(n);
    EXPECT_NEAR(e.r, std::numbers::pi * 0.5, 1e-4);
    EXPECT_NEAR(e.g, std::numbers::pi * 1.0, 1e-4);
    EXPECT_NEAR(e.b, std::numbers::pi * 2.0, 1e-4);
  }
}

TEST(IrradianceSH, LinearRadianceIsExact) {
  // L = a + b.d: integral of (a + b.w) max(0, n.w) dw = pi a + (2 pi / 3) b.n. The midpoint rule
  // on 64 x 128 cells integrates these smooth terms to O(h^2) = (pi / 64)^2 / 24 ~ 1e-4 relative.
  const Vec3 b{0.3f, 0.4f, -0.2f};
  const auto sh = IrradianceSH::project([&](const Vec3& d) { return Rgb::gray(1.0f + dot(b, d)); });
  for (const Vec3& n : kNormals) {
    const double expected = std::numbers::pi + 2.0 * std::numbers::pi / 3.0 * dot(b, n);
    EXPECT_NEAR(sh.irradiance(n).g, expected, 1e-3 * std::numbers::pi) << n.x << " " << n.y;
  }
}

TEST(IrradianceSH, SkyGradientWithinTheTruncationBound) {
  // Sky: L = h + (z - h) sin(el)^e above, g below. Facing up, E = 2 pi (h / 2 + (z - h) / (e + 2))
  // exactly. The order-2 series errs by integral L(w) (K - K2)(n.w) dw with K the clamped cosine
  // and K2 its projection 1/4 + t/2 + (5/16)(3t^2 - 1)/2; K - K2 integrates to 0, so
  // |error| <= (L_max - L_min) / 2 * 2 pi integral_{-1}^{1} |K - K2| dt.
  const double h = 0.8, z = 0.2, g = 0.3, e = 0.5;
  const auto sh = IrradianceSH::project([&](const Vec3& d) {
    const double l = d.y >= 0 ? h + (z - h) * std::pow(double(d.y), e) : g;
    return Rgb::gray(float(l));
  });
  double k_error = 0.0;
  const int steps = 20000;
  for (int i = 0; i < steps; ++i) {
    const double t = -1.0 + (i + 0.5) * 2.0 / steps;
    const double k2 = 0.25 + 0.5 * t + 5.0 / 16.0 * (3.0 * t * t - 1.0) / 2.0;
    k_error += std::abs(std::max(t, 0.0) - k2) * 2.0 / steps;
  }
  const double bound =
      (std::max({h, z, g}) - std::min({h, z, g})) / 2.0 * 2.0 * std::numbers::pi * k_error;
  const double exact_up = 2.0 * std::numbers::pi * (h / 2.0 + (z - h) / (e + 2.0));
  EXPECT_NEAR(sh.irradiance({0, 1, 0}).g, exact_up, bound);
}

}  // namespace
}  // namespace thaw::render
