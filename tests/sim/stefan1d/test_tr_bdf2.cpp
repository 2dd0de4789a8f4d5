// TR-BDF2 (sim/stefan1d/tr_bdf2.h) on plain ODEs, as MFEM's test_ode.cpp does for its steppers:
// the observed order on a nonlinear problem with an exact solution, and L-stability on a stiff
// linear one. The front-fixing solver takes its steps through the same tr_bdf2_step.
#include "sim/stefan1d/tr_bdf2.h"

#include <gtest/gtest.h>

#include <cmath>

namespace thaw::sim::stefan1d {
namespace {

/// y' = f(y) for a scalar y, each implicit stage y - beta f(y) = rhs solved by Newton to round-off.
template <class F, class DF>
struct ScalarOde {
  using State = double;
  using Rates = double;
  struct Record {
    int stages = 0;
  };
  F f;
  DF df;

  Rates rates(const State& y) const { return f(y); }
  State predict(const State& y0, const Rates& r0, double tau) const { return y0 + tau * r0; }
  bool solve(double rhs, double beta, State& y) const {
    for (int it = 0; it < 50; ++it) {
      const double g = y - beta * f(y) - rhs;
      const double step = g / (1.0 - beta * df(y));
      y -= step;
      if (std::abs(step) <= 1e-15 * (1.0 + std::abs(y))) return true;
    }
    return false;
  }
  bool solve_trapezoid_stage(const State& y0, const Rates& r0, double beta, State& yg,
                             Record& rec) const {
    rec.stages = 1;
    return solve(y0 + beta * r0, beta, yg);
  }
  State extrapolate(const State& y0, const State& yg, double) const {
    return y0 + (yg - y0) / TrBdf2::gamma;
  }
  bool solve_bdf2_stage(const State& y0, const State& yg, double beta, State& y1,
                        Record& rec) const {
    rec.stages = 1;
    return solve(TrBdf2::a * yg + TrBdf2::b * y0, beta, y1);
  }
  static Record combine(const Record& a, const Record& b) { return Record{a.stages + b.stages}; }
};

template <class F, class DF>
ScalarOde<F, DF> make_ode(F f, DF df) {
  return ScalarOde<F, DF>{f, df};
}

/// Integrates y' = -y^2, y(0) = 1 to t = 1 in n steps; the exact solution is 1 / (1 + t).
double error_of_riccati(int n) {
  auto ode = make_ode([](double y) { return -y * y; }, [](double y) { return -2.0 * y; });
  double y = 1.0;
  const double dt = 1.0 / n;
  for (int i = 0; i < n; ++i) {
    double y1 = 0;
    decltype(ode)::Record rec;
    EXPECT_TRUE(tr_bdf2_step(ode, y, dt, y1, rec));
    EXPECT_EQ(rec.stages, 2);
    y = y1;
  }
  return std::abs(y - 0.5);
}

TEST(TrBdf2, CoefficientsMakeBdf2ConsistentAndGammaTwoMinusRootTwo) {
  EXPECT_NEAR(TrBdf2::gamma, 2.0 - std::sqrt(2.0), 1e-16);
  // a + b = 1: a constant solution stays constant through the BDF2 stage.
  EXPECT_NEAR(TrBdf2::a + TrBdf2::b, 1.0, 1e-15);
}

TEST(TrBdf2, ObservedOrderIsTwoOnANonlinearOde) {
  // Second order: halving the step divides the error by 4. The leading error term's relative
  // correction is O(dt): at dt = 1/160 the observed order is 2 within a few dt, so 0.05.
  double previous = error_of_riccati(20);
  double order = 0;
  for (int n : {40, 80, 160}) {
    const double e = error_of_riccati(n);
    order = std::log2(previous / e);
    previous = e;
  }
  EXPECT_NEAR(order, 2.0, 0.05);
  EXPECT_LT(previous, 1e-5);
}

TEST(TrBdf2, IsLStableOnAStiffLinearOde) {
  // y' = lambda y with lambda dt = -1e6: an L-stable method damps the step's amplification
  // R(z) -> 0 as z -> -inf; TR-BDF2's R(z) ~ O(1/z) there, so |R| is of order 1e-6.
  const double lambda = -1e6;
  auto ode =
      make_ode([lambda](double y) { return lambda * y; }, [lambda](double) { return lambda; });
  double y1 = 0;
  decltype(ode)::Record rec;
  ASSERT_TRUE(tr_bdf2_step(ode, 1.0, 1.0, y1, rec));
  EXPECT_LT(std::abs(y1), 1e-5);
  // A-stable: never amplifies, for any step.
  for (double z : {-0.1, -1.0, -10.0, -100.0}) {
    auto mild = make_ode([z](double y) { return z * y; }, [z](double) { return z; });
    decltype(mild)::Record mild_rec;
    ASSERT_TRUE(tr_bdf2_step(mild, 1.0, 1.0, y1, mild_rec));
    EXPECT_LT(std::abs(y1), 1.0) << "z = " << z;
  }
}

}  // namespace
}  // namespace thaw::sim::stefan1d
