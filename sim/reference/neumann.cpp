#include "sim/reference/neumann.h"

#include <cmath>
#include <numbers>

#include "base/check.h"

namespace thaw::sim {

namespace {
// exp(-x^2) / erfc(x) without overflow: for large x, erfc(x) ~ exp(-x^2)/(x sqrt(pi)) *
// (1 - 1/(2x^2) + 3/(4x^4)), so the ratio tends to x sqrt(pi) / (1 - 1/(2x^2) + 3/(4x^4)).
double exp_over_erfc(double x) {
  if (x < 20.0) return std::exp(-x * x) / std::erfc(x);
  const double x2 = x * x;
  return x * std::sqrt(std::numbers::pi) / (1.0 - 1.0 / (2 * x2) + 3.0 / (4 * x2 * x2));
}
}  // namespace

double NeumannSolution::front(double t) const {
  return 2.0 * lambda * std::sqrt(alpha1() * t);
}

double NeumannSolution::front_speed(double t) const {
  return lambda * std::sqrt(alpha1() / t);
}

double NeumannSolution::time_of_front(double s) const {
  const double q = s / (2.0 * lambda);
  return q * q / alpha1();
}

double NeumannSolution::temperature(double x, double t) const {
  const double s = front(t);
  if (x <= s) {
    if (lambda == 0) return melting_point;
    return face_temperature + (melting_point - face_temperature) *
                                  std::erf(x / (2.0 * std::sqrt(alpha1() * t))) / std::erf(lambda);
  }
  const double nu = std::sqrt(alpha1() / alpha2());
  return far_temperature + (melting_point - far_temperature) *
                               std::erfc(x / (2.0 * std::sqrt(alpha2() * t))) /
                               std::erfc(nu * lambda);
}

double NeumannSolution::face_heat_flux(double t) const {
  if (lambda == 0) return 0.0;
  return k1 * (face_temperature - melting_point) /
         (std::erf(lambda) * std::sqrt(std::numbers::pi * alpha1() * t));
}

double NeumannSolution::face_heat(double t) const {
  return 2.0 * t * face_heat_flux(t);
}

NeumannSolution solve_neumann(double k1, double c1, double k2, double c2, double lv, double t_face,
                              double t_m, double t_far) {
  THAW_CHECK(k1 > 0 && c1 > 0 && k2 > 0 && c2 > 0 && lv > 0, "positive properties");
  THAW_CHECK((t_face - t_m) * (t_far - t_m) <= 0, "face and far field on opposite sides of T_m");
  NeumannSolution n{k1, c1, k2, c2, lv, t_face, t_m, t_far, 0.0};
  const double st1 = c1 * std::abs(t_face - t_m) / lv;
  const double st2 = c2 * std::abs(t_m - t_far) / lv;
  if (st1 == 0) return n;
  const double nu = std::sqrt(n.alpha1() / n.alpha2());
  const double sqrt_pi = std::sqrt(std::numbers::pi);
  // f decreases monotonically from +inf (l -> 0+) to -inf: bracket, then bisect to round-off.
  auto f = [&](double l) {
    return st1 * std::exp(-l * l) / std::erf(l) - st2 * exp_over_erfc(nu * l) / nu - l * sqrt_pi;
  };
  double lo = 1e-300, hi = 1.0;
  while (f(hi) > 0) hi *= 2;
  for (int i = 0; i < 400 && hi - lo > 4e-16 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0 ? lo : hi) = mid;
  }
  n.lambda = 0.5 * (lo + hi);
  return n;
}

}  // namespace thaw::sim
