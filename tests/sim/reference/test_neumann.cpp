// The Neumann similarity solution (sim/reference/neumann.h) checked against its own defining
// equations: the transcendental equation, the front temperature, the Stefan condition, the
// one-phase limit and the global energy balance. Everything else in the validation leans on it.
#include "sim/reference/neumann.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace thaw::sim {
namespace {

// Properties of water and ice (data/materials/ice_water.toml).
constexpr double kWater = 0.56, cWater = 1000.0 * 4186.0;
constexpr double kIce = 2.22, cIce = 917.0 * 2050.0;
constexpr double kLatent = 917.0 * 333400.0;

// One-sided second-order differences at the front, from the phase on `side` (-1 liquid side,
// +1 far side): truncation ~ h^2 |T'''| ~ 1e-10 relative, round-off ~ 1e-16 / 1e-5 ~ 1e-11.
double dTdx_at_front(const NeumannSolution& n, double t, int side) {
  const double s = n.front(t), h = 1e-5 * s;
  const double f0 = n.temperature(s, t), f1 = n.temperature(s + side * h, t),
               f2 = n.temperature(s + 2 * side * h, t);
  return side * (-3 * f0 + 4 * f1 - f2) / (2 * h);
}

TEST(Neumann, RootSatisfiesTranscendentalEquation) {
  for (double dt_face : {1.0, 10.0, 50.0})
    for (double dt_far : {0.0, 5.0, 20.0}) {
      const auto n = solve_neumann(kWater, cWater, kIce, cIce, kLatent, dt_face, 0.0, -dt_far);
      const double st1 = cWater * dt_face / kLatent, st2 = cIce * dt_far / kLatent;
      const double nu = std::sqrt(n.alpha1() / n.alpha2()), l = n.lambda;
      const double lhs = st1 * std::exp(-l * l) / std::erf(l) -
                         st2 * std::exp(-nu * nu * l * l) / (nu * std::erfc(nu * l));
      // bisection to round-off in lambda: residual ~ eps * |df/dl| ~ 1e-15
      EXPECT_NEAR(lhs, l * std::sqrt(std::numbers::pi), 1e-12) << dt_face << " " << dt_far;
    }
}

TEST(Neumann, FrontIsAtMeltingPointAndObeysStefanCondition) {
  for (bool melting : {true, false}) {
    const auto n = melting ? solve_neumann(kWater, cWater, kIce, cIce, kLatent, 15.0, 0.0, -7.0)
                           : solve_neumann(kIce, cIce, kWater, cWater, kLatent, -15.0, 0.0, 4.0);
    const double t = 500.0, s = n.front(t);
    EXPECT_NEAR(n.temperature(s, t), 0.0, 1e-12);
    EXPECT_NEAR(n.temperature(s * (1 + 1e-12), t), 0.0, 1e-9);  // continuous across the front
    // Stefan condition: L_v ds/dt = k2 dT/dx(s+) - k1 dT/dx(s-) when melting (phase 1 = water),
    // sign reversed when freezing. Differences accurate to ~1e-10: assert 1e-7 relative.
    const double jump = n.k2 * dTdx_at_front(n, t, +1) - n.k1 * dTdx_at_front(n, t, -1);
    const double lhs = kLatent * n.front_speed(t) * (melting ? 1.0 : -1.0);
    EXPECT_NEAR(jump, lhs, 1e-7 * std::abs(lhs));
  }
}

TEST(Neumann, OnePhaseLimitMatchesClassicalEquation) {
  // Far phase at T_m: lambda exp(lambda^2) erf(lambda) = St / sqrt(pi) (Crank 1984, eq. 1.21).
  for (double st : {0.01, 0.1, 1.0}) {
    const double dt = st * kLatent / cIce;
    const auto n = solve_neumann(kIce, cIce, kWater, cWater, kLatent, -dt, 0.0, 0.0);
    const double l = n.lambda;
    EXPECT_NEAR(l * std::exp(l * l) * std::erf(l), st / std::sqrt(std::numbers::pi), 1e-14);
  }
}

TEST(Neumann, HeatThroughFaceEqualsLatentPlusSensibleHeat) {
  // Energy: the heat through the face in [0, t] melts L_v s(t) and changes the sensible heat of
  // both phases (all was ice at T_far). Composite Simpson, 20000 panels: error << 1e-9 relative.
  const auto n = solve_neumann(kWater, cWater, kIce, cIce, kLatent, 20.0, 0.0, -10.0);
  const double t = 800.0, s = n.front(t), far = s + 12.0 * std::sqrt(n.alpha2() * t);
  auto sensible = [&](double a, double b, double cap, double t_init) {
    const int m = 20000;
    const double h = (b - a) / m;
    double sum = 0;
    for (int i = 0; i <= m; ++i) {
      const double w = (i == 0 || i == m) ? 1 : (i % 2 ? 4 : 2);
      sum += w * cap * (n.temperature(a + i * h, t) - t_init);
    }
    return sum * h / 3;
  };
  const double q =
      kLatent * s + cIce * 10.0 * s + sensible(0, s, cWater, 0.0) + sensible(s, far, cIce, -10.0);
  EXPECT_NEAR(n.face_heat(t), q, 1e-9 * q);
}

}  // namespace
}  // namespace thaw::sim
