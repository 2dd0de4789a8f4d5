// Dispersion through a prism: a ray traced with vector Snell refraction at both faces, minimised
// over the angle of incidence, gives the closed-form minimum deviation for n(lambda) from the
// library; blue is deviated more than red by the amount the Abbe number predicts.
#include <gtest/gtest.h>

#include <cmath>

#include "render/format/medium_library.h"
#include "render/media/refraction.h"

namespace thaw::render::optics {
namespace {

/// Minimum over incidence of the traced deviation (golden-section search; deviation is
/// unimodal in the incidence angle for a prism).
double traced_minimum_deviation(double n, double apex) {
  double lo = 0.0, hi = 1.5;  // rad
  const double g = (std::sqrt(5.0) - 1) / 2;
  auto f = [&](double i) { return prism_deviation_rad(n, apex, i).value_or(10.0); };
  double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
  for (int k = 0; k < 200; ++k) {
    if (f(a) < f(b))
      hi = b;
    else
      lo = a;
    a = hi - g * (hi - lo);
    b = lo + g * (hi - lo);
  }
  return f(0.5 * (lo + hi));
}

TEST(Prism, TracedMinimumDeviationMatchesFormula) {
  const double apex = M_PI / 3;  // 60 degree equilateral prism
  for (const char* name : {"n-bk7", "n-sf10", "water-20c", "ice-ih"}) {
    const auto& ior = *media::find_medium_preset(name)->ior;
    for (double l : {400.0, 486.1327, 587.5618, 656.2725, 760.0}) {
      const double n = ior.n_at(l);
      // The golden-section minimum is flat (quadratic), so the deviation is found to ~1e-12.
      EXPECT_NEAR(traced_minimum_deviation(n, apex), prism_minimum_deviation_rad(n, apex), 1e-9)
          << name << " " << l;
    }
  }
}

TEST(Prism, BlueDeviatesMoreAndSpreadFollowsAbbe) {
  const double apex = M_PI / 3;
  const auto& sf10 = *media::find_medium_preset("n-sf10")->ior;
  const double d_f = prism_minimum_deviation_rad(sf10.n_at(486.1327), apex);
  const double d_c = prism_minimum_deviation_rad(sf10.n_at(656.2725), apex);
  EXPECT_GT(d_f, d_c);
  // Thin-prism estimate of the angular spread: (n_F - n_C) * dD/dn, dD/dn = 2 sin(A/2)/cos(...)
  // at minimum deviation; the exact spread agrees with it to second order in n_F - n_C.
  const double n_d = sf10.n_at(587.5618);
  const double d_d = prism_minimum_deviation_rad(n_d, apex);
  const double ddn = 2 * std::sin(apex / 2) / std::cos((apex + d_d) / 2);
  const double spread_estimate = (n_d - 1) / sf10.abbe_number() * ddn;
  EXPECT_NEAR(d_f - d_c, spread_estimate, 0.02 * spread_estimate);
}

TEST(Snell, RefractAndTotalInternalReflection) {
  // 45 degrees from glass (1.5) into air: sin t = 1.5 sin 45 > 1, total internal reflection.
  const Vec2 d{std::sin(M_PI / 4), -std::cos(M_PI / 4)};
  const Vec2 n{0, 1};
  EXPECT_FALSE(refract(d, n, 1.5, 1.0).has_value());
  // Air into water at 30 degrees: sin t = sin 30 / 1.333.
  const Vec2 d30{std::sin(M_PI / 6), -std::cos(M_PI / 6)};
  const auto t = refract(d30, n, 1.0, 1.333);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(t->x, 0.5 / 1.333, 1e-12);
  EXPECT_NEAR(t->x * t->x + t->y * t->y, 1.0, 1e-12);
}

}  // namespace
}  // namespace thaw::render::optics
