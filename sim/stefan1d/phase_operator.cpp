#include "sim/stefan1d/phase_operator.h"

#include "base/check.h"

namespace thaw::sim::stefan1d {

// One-sided second-order gradient at a Dirichlet face from the face value and the two nearest
// cell centres (distances dx/2 and 3dx/2): du/dn = (-8 u_b + 9 u_1 - u_2) / (3 dx) (inward normal).
// Robin: k du/dn_out = htc (u_air - u_b) with the same stencil, solved for u_b.
BoundaryForm boundary_form(const Bc& bc, double k, double area, double dx) {
  BoundaryForm f;
  const double kappa = k / (3.0 * dx);
  switch (bc.kind) {
    case BcKind::zero_flux:
      break;
    case BcKind::dirichlet:
      f.q0 = area * 8.0 * kappa * bc.value;
      f.p1 = -area * 9.0 * kappa;
      f.p2 = area * kappa;
      break;
    case BcKind::robin: {
      const double d = bc.htc + 8.0 * kappa;
      f.q0 = area * bc.htc * bc.value * (8.0 * kappa / d);
      f.p1 = -area * bc.htc * 9.0 * kappa / d;
      f.p2 = area * bc.htc * kappa / d;
      break;
    }
    case BcKind::flux:
      f.q0 = area * bc.value;
      break;
    case BcKind::air:
      THAW_CHECK(false, "the air boundary is linearised before its stencil is formed");
  }
  return f;
}

double boundary_value(const Bc& bc, double k, double dx, double u1, double u2) {
  const double kappa = k / (3.0 * dx);
  switch (bc.kind) {
    case BcKind::dirichlet:
      return bc.value;
    case BcKind::robin:
      return (bc.htc * bc.value + kappa * (9.0 * u1 - u2)) / (bc.htc + 8.0 * kappa);
    case BcKind::flux:
      return (bc.value / kappa + 9.0 * u1 - u2) / 8.0;
    case BcKind::zero_flux:
      return (9.0 * u1 - u2) / 8.0;
    case BcKind::air:
      THAW_CHECK(false, "the air boundary is linearised before its face value is taken");
  }
  return 0;
}

OperatorValue apply_operator(const Radial& g, const Phase& p, double a, double e, const Bc& left,
                             const Bc& right, const std::vector<double>& u) {
  const int n = p.n;
  const double dx = (e - a) / n;
  OperatorValue out;
  out.d.assign(n, 0.0);
  for (int f = 1; f < n; ++f) {
    const double flux = p.k * g.area(face_r(a, e, n, f)) * (u[f] - u[f - 1]) / dx;
    out.d[f - 1] += flux;
    out.d[f] -= flux;
  }
  out.q_left = boundary_form(left, p.k, g.area(a), dx).eval(u[0], u[1]);
  out.q_right = boundary_form(right, p.k, g.area(e), dx).eval(u[n - 1], u[n - 2]);
  out.d[0] += out.q_left;
  out.d[n - 1] += out.q_right;
  return out;
}

void solve_tridiagonal(std::vector<double>& lower, std::vector<double>& diag,
                       std::vector<double>& upper, std::vector<double>& rhs,
                       std::vector<double>& x) {
  const std::size_t n = diag.size();
  for (std::size_t i = 1; i < n; ++i) {
    const double w = lower[i] / diag[i - 1];
    diag[i] -= w * upper[i - 1];
    rhs[i] -= w * rhs[i - 1];
  }
  x.resize(n);
  x[n - 1] = rhs[n - 1] / diag[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) x[i] = (rhs[i] - upper[i] * x[i + 1]) / diag[i];
}

}  // namespace thaw::sim::stefan1d
