#pragma once
// TR-BDF2 (Bank et al. 1985, IEEE Trans. Electron Devices 32; Hosea & Shampine 1996, Appl. Numer.
// Math. 20) written once, for any problem that can solve its two implicit stages: a trapezoidal
// stage to t + gamma dt, then BDF2 through t, t + gamma dt, t + dt:
//   y_g - (gamma dt / 2) f(y_g) = y_0 + (gamma dt / 2) f(y_0)
//   y_1 - c dt f(y_1)           = a y_g + b y_0
// gamma = 2 - sqrt(2) makes both stages share one Jacobian scaling and the method L-stable, so
// discontinuous initial data (a warm core in a cold shell) does not ring. Second order.
// Knows nothing of fronts, phases or Stefan problems: the front-fixing solver and a plain ODE
// (tests/sim/stefan1d/test_tr_bdf2.cpp, which asserts the observed order) use the same step.

namespace thaw::sim::stefan1d {

struct TrBdf2 {
  static constexpr double gamma = 0.58578643762690485;  // 2 - sqrt(2)
  static constexpr double a = 1.0 / (gamma * (2.0 - gamma));
  static constexpr double b = -(1.0 - gamma) * (1.0 - gamma) / (gamma * (2.0 - gamma));
  static constexpr double c = (1.0 - gamma) / (2.0 - gamma);
};

/// One TR-BDF2 step of size dt from y0 into y1. The problem P supplies, with its own State,
/// Rates (f at a state) and Record (what a stage books, e.g. heat):
///   Rates rates(const State& y0);
///   State predict(const State& y0, const Rates& r0, double tau);     // guess at t0 + tau
///   bool solve_trapezoid_stage(const State& y0, const Rates& r0, double beta, State& yg,
///                              Record& rec);   // y - beta f(y) = y0 + beta f(y0)
///   State extrapolate(const State& y0, const State& yg, double dt);  // guess at t0 + dt
///   bool solve_bdf2_stage(const State& y0, const State& yg, double beta, State& y1,
///                         Record& rec);   // y - beta f(y) = a yg + b y0
///   Record combine(const Record& trapezoid, const Record& bdf2);     // the whole step's
/// Returns false when a stage fails (the caller shortens the step).
template <class P>
bool tr_bdf2_step(P& problem, const typename P::State& y0, double dt, typename P::State& y1,
                  typename P::Record& record) {
  const typename P::Rates r0 = problem.rates(y0);
  typename P::State yg = problem.predict(y0, r0, TrBdf2::gamma * dt);
  typename P::Record trapezoid, bdf2;
  if (!problem.solve_trapezoid_stage(y0, r0, 0.5 * TrBdf2::gamma * dt, yg, trapezoid)) return false;
  y1 = problem.extrapolate(y0, yg, dt);
  if (!problem.solve_bdf2_stage(y0, yg, TrBdf2::c * dt, y1, bdf2)) return false;
  record = problem.combine(trapezoid, bdf2);
  return true;
}

}  // namespace thaw::sim::stefan1d
