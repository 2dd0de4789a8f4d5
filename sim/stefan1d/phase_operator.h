#pragma once
// The Landau-transformed phase operator of the 1D front-fixing solver: one phase (water or ice)
// between its moving ends a < e, split into n equal cells that stretch with it, in radial
// geometry r^m. Evaluates the conducted heat into each cell and through both ends, the boundary
// conditions as affine forms of the nearest cells (one-sided second-order gradients), and the
// tridiagonal solve its implicit stages need. Knows nothing of fronts, time stepping or events
// (sim/stefan1d/front_fixing.cpp) nor of scenarios and files.
#include <numbers>
#include <vector>

namespace thaw::sim::stefan1d {

/// Radial geometry r^m: planar m = 0, cylinder m = 1, sphere m = 2. Per unit solid angle (and
/// per unit length / area): face area A(r) = r^m, volume below r W(r) = r^(m+1)/(m+1).
struct Radial {
  int m = 2;
  double omega = 4 * std::numbers::pi;  ///< 1 (planar, per m^2), 2 pi (cylinder, per m), 4 pi
  double area(double r) const { return m == 0 ? 1.0 : (m == 1 ? r : r * r); }
  double w(double r) const { return m == 0 ? r : (m == 1 ? 0.5 * r * r : r * r * r / 3.0); }
};

/// air: the nonlinear flux of sim/boundary/air_model.h, q(u_b, b); the solver replaces it by its
/// tangent Robin form at the current surface value before any stencil sees it.
enum class BcKind { zero_flux, dirichlet, robin, flux, air };
/// A boundary condition on u = T - T_m.
struct Bc {
  BcKind kind = BcKind::zero_flux;
  double value = 0;  ///< dirichlet: u; robin: u_air; flux: heat flux into the region [W/m^2]
  double htc = 0;    ///< robin: heat transfer coefficient [W/(m^2 K)]
};

/// Heat rate into a region through one boundary face as an affine form of its two nearest cell
/// values: Q = q0 + p1 * u(nearest) + p2 * u(next) [W per unit solid angle].
struct BoundaryForm {
  double q0 = 0, p1 = 0, p2 = 0;
  double eval(double u1, double u2) const { return q0 + p1 * u1 + p2 * u2; }
};

/// One phase's material and resolution: conductivity k [W/(m K)], volumetric heat capacity
/// [J/(m^3 K)], n equal cells (Landau transform: faces at a + f (e - a) / n).
struct Phase {
  double k = 0, heat_capacity = 0;
  int n = 0;
};

/// Position of face f of a phase [a, e] with n cells [m].
inline double face_r(double a, double e, int n, int f) {
  return a + (e - a) * f / n;
}

/// Heat rate into the phase through a boundary face of area `area` (per unit solid angle) as an
/// affine form of the two nearest cells of width dx [m].
BoundaryForm boundary_form(const Bc& bc, double k, double area, double dx);
/// Face value of u at a boundary face (for profiles): Dirichlet value, Robin/flux extrapolation.
double boundary_value(const Bc& bc, double k, double dx, double u1, double u2);

/// Conducted heat into each cell and through both ends of a phase at one state.
struct OperatorValue {
  std::vector<double> d;           ///< net conducted heat rate into cell j
  double q_left = 0, q_right = 0;  ///< heat rate into the phase through its ends
};

/// The phase operator at cell values u (u = T - T_m, n entries) between ends a < e.
OperatorValue apply_operator(const Radial& g, const Phase& p, double a, double e, const Bc& left,
                             const Bc& right, const std::vector<double>& u);

/// Solves the tridiagonal system (Thomas algorithm; the phase systems are diagonally dominant).
/// Overwrites diag and rhs.
void solve_tridiagonal(std::vector<double>& lower, std::vector<double>& diag,
                       std::vector<double>& upper, std::vector<double>& rhs,
                       std::vector<double>& x);

}  // namespace thaw::sim::stefan1d
