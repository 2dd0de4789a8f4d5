#include "sim/stefan1d/front_fixing.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "base/check.h"
#include "base/error.h"
#include "sim/boundary/scenario_air.h"
#include "sim/reference/neumann.h"
#include "sim/scenario/scenario_rules.h"
#include "sim/stefan1d/phase_operator.h"
#include "sim/stefan1d/tr_bdf2.h"

namespace thaw::sim {

namespace {

using stefan1d::apply_operator;
using stefan1d::Bc;
using stefan1d::BcKind;
using stefan1d::boundary_form;
using stefan1d::boundary_value;
using stefan1d::BoundaryForm;
using stefan1d::face_r;
using stefan1d::OperatorValue;
using stefan1d::Phase;
using stefan1d::Radial;
using stefan1d::solve_tridiagonal;
using stefan1d::TrBdf2;

/// A phase that gets thinner than this fraction of the initial outer radius is removed (its
/// remaining enthalpy is booked as "removed"); zero-thickness phases start at this thickness.
constexpr double kRemnantFraction = 1e-6;

/// Runaway guard: after every window of kGuardWindowCost (attempted steps x cells per phase,
/// about 2 s of solver time), the attempts still needed at the pace of that window are
/// projected; beyond kGuardMaxCost (about 40 minutes, measured 0.23 ms per attempt at 48 cells
/// on the 2-core CI machine) the step has collapsed and the run would never end in practice.
constexpr double kGuardWindowCost = 5e5;
constexpr double kGuardMaxCost = 5e8;

/// The solver cannot continue on this scenario (caught in FrontFixingSolver::advance_to and
/// turned into a UserError naming the likely key).
struct Breakdown {
  std::string what;
};

std::string seconds_text(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g s", t);
  return buf;
}

/// The root of a function f that falls through zero once, from a guess: Newton steps
/// (central-difference slope) kept inside a bracket that is widened until it holds the root,
/// bisection when a step leaves it. Converged when the step or the bracket is below `tol`.
template <class F>
double decreasing_root(F&& f, double guess, double tol) {
  double lo = guess, hi = guess, flo = f(lo), fhi = flo;
  double width = std::max(1.0, std::abs(guess));
  while (flo < 0) {  // the root lies below
    hi = lo, fhi = flo;
    lo -= width, width *= 2, flo = f(lo);
    if (width > 1e9) return lo;
  }
  width = std::max(1.0, std::abs(guess));
  while (fhi > 0) {  // the root lies above
    lo = hi, flo = fhi;
    hi += width, width *= 2, fhi = f(hi);
    if (width > 1e9) return hi;
  }
  double x = std::clamp(guess, lo, hi);
  for (int it = 0; it < 100; ++it) {
    const double fx = f(x);
    if (fx == 0) return x;
    (fx > 0 ? lo : hi) = x;
    // a slope over 1e-4 K: accurate to ~1e-8 relative for the smooth fluxes here, and far above
    // the round-off of the differences (a tiny d would let a noisy slope fake convergence)
    const double d = 1e-4;
    const double slope = (f(x + d) - f(x - d)) / (2 * d);
    double next = slope < 0 ? x - fx / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const double step = std::abs(next - x);
    x = next;
    if (step < tol || hi - lo < tol) return x;
  }
  return x;
}

/// The complete discrete state.
struct State {
  double t = 0;
  double s = 0;                ///< water|ice front [m] (0 without liquid)
  double b = 0;                ///< ice surface [m]
  bool liquid = false;         ///< a liquid core exists
  bool ablating = false;       ///< the ice surface is at T_m and recedes (melt drains)
  std::vector<double> ul, ui;  ///< cell values of u = T - T_m [K]
};

/// Energy bookkeeping of one stage or step, per unit solid angle [J].
struct Heat {
  double in = 0;       ///< heat through the boundaries
  double drained = 0;  ///< enthalpy carried off by drained melt
};

}  // namespace

struct FrontFixingSolver::Impl {
  using State = sim::State;  // the problem type of tr_bdf2_step
  Scenario sc;
  Radial geo;
  Phase water, ice;
  double latent = 0;             ///< rho_ice L [J/m^3]
  double t_m = 0;                ///< melting point [C]
  double length_scale = 0;       ///< b0 [m]
  double temperature_scale = 1;  ///< [K]
  double remnant = 0;            ///< thickness below which a phase is removed [m]
  double tol = 1e-6;
  Bc inner_bc;                    ///< at r = 0
  Bc outer_bc;                    ///< at r = b when not ablating
  double ablation_heat_flux = 0;  ///< heat flux arriving at a surface held at T_m [W/m^2]
  Air air;                        ///< outer_kind == air: the room (sim/boundary/air_model.h)

  // --- the air boundary (kind = air): q(u_b, b) depends on the surface value and the size ---
  /// Heat flux from the air into the ice surface at u = T - T_m, radius b [W/m^2].
  double air_flux(double u, double b) const {
    return air_heat_flux(air, radial_air_body(sc, b), u + t_m).total_w_m2();
  }
  /// Heat flux arriving at the ice surface at radius b when it is held at T_m [W/m^2].
  double arriving_flux(double b) const {
    return outer_bc.kind == BcKind::air ? air_flux(0.0, b) : ablation_heat_flux;
  }
  /// Heat arrives at a surface held at T_m and can melt it away (drained).
  bool can_ablate() const {
    return (outer_bc.kind == BcKind::robin || outer_bc.kind == BcKind::flux ||
            outer_bc.kind == BcKind::air) &&
           arriving_flux(st.b) > 0;
  }
  /// The air's tangent at surface value u as a Robin condition: q = htc (u_eff - u_b), exact in
  /// value and slope at u_b = u where htc = -dq/du, Newton's linearisation of the boundary (the
  /// iteration converges quadratically). The slope is at least the convective h: within ~1 K of
  /// the air's temperature, evaporation (h_m ~ |dT|^(1/4)) can make q rise with the surface's
  /// temperature, and a chord then converges where a tangent of the wrong sign would not.
  Bc air_tangent(double u, double b) const {
    const double du = 1e-4;
    const AirFlux f = air_heat_flux(air, radial_air_body(sc, b), u + t_m);
    const double q = f.total_w_m2();
    const double htc = std::max(-(air_flux(u + du, b) - air_flux(u - du, b)) / (2 * du),
                                f.heat_transfer_coefficient_w_m2k);
    return Bc{BcKind::robin, u + q / htc, htc};
  }
  /// The ice's outer condition when not ablating, with the air replaced by its tangent at the
  /// surface value the cells u1, u2 (nearest first, width dx) give: the root of
  /// q(u_b) = k (8 u_b - 9 u1 + u2) / (3 dx) (the second-order one-sided stencil).
  Bc outer_bc_at(double u1, double u2, double dx, double b) const {
    if (outer_bc.kind != BcKind::air) return outer_bc;
    const double kappa = ice.k / (3.0 * dx);
    const double ub = decreasing_root(
        [&](double u) { return air_flux(u, b) - kappa * (8.0 * u - 9.0 * u1 + u2); }, u1,
        1e-13 * temperature_scale);
    return air_tangent(ub, b);
  }

  State st;
  double next_dt = 0;  ///< the step to try next [s]
  bool done = false;
  std::vector<Event> events;
  SolverStatistics stats;
  double e0 = 0;                    ///< total enthalpy at t = 0 [J per unit solid angle]
  double heat_in = 0, drained = 0;  ///< cumulative, per unit solid angle

  // --- per-state helpers -------------------------------------------------------------------
  double ice_left(const State& x) const { return x.liquid ? x.s : 0.0; }
  Bc ice_left_bc(const State& x) const {
    return x.liquid ? Bc{BcKind::dirichlet, 0.0, 0.0} : inner_bc;
  }
  Bc ice_right_bc(const State& x) const {
    if (x.ablating) return Bc{BcKind::dirichlet, 0.0, 0.0};
    const double dx = (x.b - ice_left(x)) / ice.n;
    return outer_bc_at(x.ui[ice.n - 1], x.ui[ice.n - 2], dx, x.b);
  }
  static Bc front_bc() { return Bc{BcKind::dirichlet, 0.0, 0.0}; }

  double phase_energy(const Phase& p, double a, double e, const std::vector<double>& u) const {
    double sum = 0;
    for (int j = 0; j < p.n; ++j)
      sum +=
          p.heat_capacity * u[j] * (geo.w(face_r(a, e, p.n, j + 1)) - geo.w(face_r(a, e, p.n, j)));
    return sum;
  }
  /// Total enthalpy relative to ice at T_m, per unit solid angle [J].
  double energy(const State& x) const {
    double e = phase_energy(ice, ice_left(x), x.b, x.ui);
    if (x.liquid) e += phase_energy(water, 0.0, x.s, x.ul) + latent * geo.w(x.s);
    return e;
  }

  /// Rates at a state: conducted heat per cell, front and ablation heat, boundary heat.
  struct Rates {
    OperatorValue wat, ic;
    double front = 0;     ///< heat absorbed by the front, -(Q_liquid + Q_ice) [W]
    double ablation = 0;  ///< heat arriving minus heat conducted into the ice at b [W]
    double boundary = 0;  ///< heat entering through r = 0 (held wall) and r = b [W]
  };
  Rates rates(const State& x) const {
    Rates r;
    r.ic = apply_operator(geo, ice, ice_left(x), x.b, ice_left_bc(x), ice_right_bc(x), x.ui);
    double q_inner = 0;
    if (x.liquid) {
      r.wat = apply_operator(geo, water, 0.0, x.s, inner_bc, front_bc(), x.ul);
      r.front = -(r.wat.q_right + r.ic.q_left);
      q_inner = r.wat.q_left;
    } else {
      q_inner = r.ic.q_left;
    }
    if (inner_bc.kind != BcKind::dirichlet) q_inner = 0;
    const double q_ext = geo.area(x.b) * arriving_flux(x.b);
    if (x.ablating) r.ablation = q_ext - r.ic.q_right;
    r.boundary = q_inner + (x.ablating ? q_ext : r.ic.q_right);
    return r;
  }

  double surface_temperature(const State& x) const {
    const double dx = (x.b - ice_left(x)) / ice.n;
    return boundary_value(ice_right_bc(x), ice.k, dx, x.ui[ice.n - 1], x.ui[ice.n - 2]);
  }

  // --- one implicit stage -------------------------------------------------------------------
  // Cell j of a phase, with E_j = C u_j V_j and W_f = W(r_f):
  //   E_j(new) - beta D_j(new) - w_new C [u_f W-sweep]_(j+1) + w_new C [..]_j = rhs_j
  // where the swept volume of face f is dW_f = W_f(new) - Wref_f; rhs holds the old-time part.
  struct StageRef {
    bool trapezoid = true;
    double beta = 0;            ///< weight of new-time rates [s]
    const State* s0 = nullptr;  ///< state at t_n
    const Rates* r0 = nullptr;  ///< rates at t_n (trapezoid)
    const State* sg = nullptr;  ///< state at t_n + gamma dt (BDF2 stage)
  };

  /// Solves one phase's cells for given end positions; returns heat through its two ends. An
  /// air condition on the right is solved with the cells, by Newton on its surface value: the
  /// tangent Robin form at the last value, one tridiagonal solve, the new face value (u_out holds
  /// the previous iterate's cells on entry, the first guess). False if that does not converge.
  bool solve_phase(const Phase& p, double a, double e, const Bc& left, const Bc& right,
                   const StageRef& ref, bool is_water, std::vector<double>& u_out, double& q_left,
                   double& q_right) {
    if (right.kind != BcKind::air) {
      solve_phase_linear(p, a, e, left, right, ref, is_water, u_out, q_left, q_right);
      return true;
    }
    const int n = p.n;
    const double dx = (e - a) / n;
    Bc tangent = outer_bc_at(u_out[n - 1], u_out[n - 2], dx, e);
    double ub = boundary_value(tangent, p.k, dx, u_out[n - 1], u_out[n - 2]);
    for (int it = 0; it < 40; ++it) {
      solve_phase_linear(p, a, e, left, tangent, ref, is_water, u_out, q_left, q_right);
      const double ub_new = boundary_value(tangent, p.k, dx, u_out[n - 1], u_out[n - 2]);
      const double change = std::abs(ub_new - ub);
      ub = ub_new;
      if (change <= 1e-12 * temperature_scale) return true;
      tangent = air_tangent(ub, e);
    }
    return false;
  }

  void solve_phase_linear(const Phase& p, double a, double e, const Bc& left, const Bc& right,
                          const StageRef& ref, bool is_water, std::vector<double>& u_out,
                          double& q_left, double& q_right) {
    const int n = p.n;
    const double dx = (e - a) / n;
    const double cap = p.heat_capacity;
    thread_local std::vector<double> lower, diag, upper, rhs, wref, wnew;
    lower.assign(n, 0.0);
    diag.assign(n, 0.0);
    upper.assign(n, 0.0);
    rhs.assign(n, 0.0);
    wnew.resize(n + 1);
    wref.resize(n + 1);
    for (int f = 0; f <= n; ++f) wnew[f] = geo.w(face_r(a, e, n, f));

    auto ends_of = [&](const State& x, double& aa, double& ee) {
      if (is_water) {
        aa = 0.0;
        ee = x.s;
      } else {
        aa = ice_left(x);
        ee = x.b;
      }
    };
    const State& x0 = *ref.s0;
    double a0, e0_;
    ends_of(x0, a0, e0_);
    const std::vector<double>& u0 = is_water ? x0.ul : x0.ui;
    double w_new_adv;
    if (ref.trapezoid) {
      const OperatorValue& op0 = is_water ? ref.r0->wat : ref.r0->ic;
      for (int f = 0; f <= n; ++f) wref[f] = geo.w(face_r(a0, e0_, n, f));
      for (int j = 0; j < n; ++j)
        rhs[j] = cap * u0[j] * (wref[j + 1] - wref[j]) + ref.beta * op0.d[j];
      // explicit half of the swept enthalpy: (1/2) C u_f(t_n) dW_f over interior faces
      for (int f = 1; f < n; ++f) {
        const double sweep = 0.5 * cap * 0.5 * (u0[f - 1] + u0[f]) * (wnew[f] - wref[f]);
        rhs[f - 1] += sweep;
        rhs[f] -= sweep;
      }
      w_new_adv = 0.5;
    } else {
      const State& xg = *ref.sg;
      double ag, eg;
      ends_of(xg, ag, eg);
      const std::vector<double>& ug = is_water ? xg.ul : xg.ui;
      for (int f = 0; f <= n; ++f)
        wref[f] =
            TrBdf2::a * geo.w(face_r(ag, eg, n, f)) + TrBdf2::b * geo.w(face_r(a0, e0_, n, f));
      for (int j = 0; j < n; ++j)
        rhs[j] = TrBdf2::a * cap * ug[j] *
                     (geo.w(face_r(ag, eg, n, j + 1)) - geo.w(face_r(ag, eg, n, j))) +
                 TrBdf2::b * cap * u0[j] *
                     (geo.w(face_r(a0, e0_, n, j + 1)) - geo.w(face_r(a0, e0_, n, j)));
      w_new_adv = 1.0;
    }
    for (int j = 0; j < n; ++j) diag[j] = cap * (wnew[j + 1] - wnew[j]);
    for (int f = 1; f < n; ++f) {
      const double c = ref.beta * p.k * geo.area(face_r(a, e, n, f)) / dx;
      diag[f - 1] += c;
      upper[f - 1] -= c;
      diag[f] += c;
      lower[f] -= c;
      const double adv = w_new_adv * cap * 0.5 * (wnew[f] - wref[f]);
      diag[f - 1] -= adv;
      upper[f - 1] -= adv;
      lower[f] += adv;
      diag[f] += adv;
    }
    const BoundaryForm fl = boundary_form(left, p.k, geo.area(a), dx);
    const BoundaryForm fr = boundary_form(right, p.k, geo.area(e), dx);
    diag[0] -= ref.beta * fl.p1;
    upper[0] -= ref.beta * fl.p2;
    rhs[0] += ref.beta * fl.q0;
    diag[n - 1] -= ref.beta * fr.p1;
    lower[n - 1] -= ref.beta * fr.p2;
    rhs[n - 1] += ref.beta * fr.q0;
    solve_tridiagonal(lower, diag, upper, rhs, u_out);
    ++stats.linear_solves;
    q_left = fl.eval(u_out[0], u_out[1]);
    q_right = fr.eval(u_out[n - 1], u_out[n - 2]);
  }

  /// Front and ablation residuals for the new positions in x (x.s, x.b); fills x's cells.
  /// Returns false if the positions are not admissible.
  bool residual(const StageRef& ref, State& x, double res[2], Heat& heat) {
    const State& x0 = *ref.s0;
    if (x.liquid && !(x.s > 0 && x.s < x.b)) return false;
    if (!(x.b > ice_left(x))) return false;
    double ql_w = 0, qr_w = 0, ql_i = 0, qr_i = 0;
    if (x.liquid) solve_phase(water, 0.0, x.s, inner_bc, front_bc(), ref, true, x.ul, ql_w, qr_w);
    const Bc right = x.ablating ? Bc{BcKind::dirichlet, 0.0, 0.0} : outer_bc;
    if (!solve_phase(ice, ice_left(x), x.b, ice_left_bc(x), right, ref, false, x.ui, ql_i, qr_i))
      return false;
    auto wref = [&](double State::*member) {
      if (ref.trapezoid) return geo.w(x0.*member);
      return TrBdf2::a * geo.w(ref.sg->*member) + TrBdf2::b * geo.w(x0.*member);
    };
    const double q_ext = geo.area(x.b) * arriving_flux(x.b);
    double q_inner = x.liquid ? ql_w : ql_i;
    if (inner_bc.kind != BcKind::dirichlet) q_inner = 0;
    const double q_boundary = q_inner + (x.ablating ? q_ext : qr_i);
    heat.in = ref.beta * q_boundary + (ref.trapezoid ? ref.beta * ref.r0->boundary : 0.0);
    heat.drained = 0;
    res[0] = res[1] = 0;
    if (x.liquid) {
      const double front_heat = -(qr_w + ql_i);
      res[0] = latent * (geo.w(x.s) - wref(&State::s)) - ref.beta * front_heat -
               (ref.trapezoid ? ref.beta * ref.r0->front : 0.0);
    }
    if (x.ablating) {
      const double abl = q_ext - qr_i;
      const double melted = -(geo.w(x.b) - wref(&State::b));  // volume drained this stage
      res[1] =
          -latent * melted + ref.beta * abl + (ref.trapezoid ? ref.beta * ref.r0->ablation : 0.0);
      heat.drained = latent * melted;
    }
    return true;
  }

  /// Newton on (s, b) with temperatures eliminated; x holds the predictor on entry.
  bool solve_stage(const StageRef& ref, State& x, Heat& heat) {
    int idx[2];
    int nz = 0;
    if (x.liquid) idx[nz++] = 0;
    if (x.ablating) idx[nz++] = 1;
    auto get = [&](const State& y, int i) { return i == 0 ? y.s : y.b; };
    auto set = [&](State& y, int i, double v) { (i == 0 ? y.s : y.b) = v; };
    double res[2];
    if (!residual(ref, x, res, heat)) return false;
    if (nz == 0) return true;
    double jac[2][2] = {{0, 0}, {0, 0}};
    bool have_jac = false;
    for (int it = 0; it < 30; ++it) {
      ++stats.newton_iterations;
      if (!have_jac || it % 6 == 5) {
        // finite-difference columns; the perturbation is a small fraction of the adjacent
        // phase thickness so the perturbed geometry stays admissible.
        for (int c = 0; c < nz; ++c) {
          State y = x;
          const double thick = idx[c] == 0 ? std::min(x.s, x.b - x.s) : x.b - ice_left(x);
          const double delta = (idx[c] == 0 ? 1e-7 : -1e-7) * thick;
          set(y, idx[c], get(x, idx[c]) + delta);
          double r2[2];
          Heat heat2;
          if (!residual(ref, y, r2, heat2)) return false;
          for (int rr = 0; rr < nz; ++rr) jac[rr][c] = (r2[idx[rr]] - res[idx[rr]]) / delta;
        }
        have_jac = true;
      }
      // The Schur complement of the bordered system: the temperatures are already eliminated
      // (exact tridiagonal solves), so Newton's matrix is nz x nz.
      double step[2] = {0, 0};
      if (nz == 1) {
        step[0] = -res[idx[0]] / jac[0][0];
      } else {
        Eigen::Matrix2d j;
        j << jac[0][0], jac[0][1], jac[1][0], jac[1][1];
        const Eigen::Vector2d d =
            j.partialPivLu().solve(Eigen::Vector2d(-res[idx[0]], -res[idx[1]]));
        step[0] = d[0];
        step[1] = d[1];
      }
      bool converged = true;
      for (int c = 0; c < nz; ++c) {
        if (!std::isfinite(step[c])) return false;
        const double z = get(x, idx[c]);
        if (std::abs(step[c]) > 1e-14 * std::abs(z) + 1e-18 * length_scale) converged = false;
      }
      if (converged) return true;
      for (int c = 0; c < nz; ++c) set(x, idx[c], get(x, idx[c]) + step[c]);
      if (!residual(ref, x, res, heat)) return false;
    }
    return false;
  }

  // --- the TR-BDF2 problem (sim/stefan1d/tr_bdf2.h): the stages of one step -------------------
  using Record = Heat;

  /// Guess at t0 + tau: front velocities from the rates at t0, kept admissible.
  State predict(const State& x0, const Rates& r0, double tau) const {
    State y = x0;
    y.t = x0.t + tau;
    if (y.liquid) y.s = x0.s + tau * r0.front / (latent * geo.area(x0.s));
    if (y.ablating) y.b = x0.b - tau * r0.ablation / (latent * geo.area(x0.b));
    if (y.liquid) y.s = std::clamp(y.s, 0.5 * x0.s, x0.s + 0.5 * (x0.b - x0.s));
    if (y.ablating) y.b = std::max(y.b, ice_left(y) + 0.5 * (x0.b - ice_left(x0)));
    return y;
  }
  bool solve_trapezoid_stage(const State& x0, const Rates& r0, double beta, State& xg, Heat& heat) {
    return solve_stage(StageRef{true, beta, &x0, &r0, nullptr}, xg, heat);
  }
  /// Guess at t0 + dt: the fronts extrapolated linearly through the trapezoid stage.
  State extrapolate(const State& x0, const State& xg, double dt) const {
    State x1 = xg;
    x1.t = x0.t + dt;
    if (x1.liquid) x1.s = x0.s + (xg.s - x0.s) / TrBdf2::gamma;
    if (x1.ablating) x1.b = x0.b + (xg.b - x0.b) / TrBdf2::gamma;
    if (x1.liquid && !(x1.s > 0 && x1.s < x1.b)) x1.s = xg.s;
    if (x1.ablating && !(x1.b > ice_left(x1))) x1.b = xg.b;
    return x1;
  }
  bool solve_bdf2_stage(const State& x0, const State& xg, double beta, State& x1, Heat& heat) {
    return solve_stage(StageRef{false, beta, &x0, nullptr, &xg}, x1, heat);
  }
  /// The step's heat: E1 - E0 = a (Eg - E0) + (E1 - a Eg - b E0), a + b = 1.
  static Heat combine(const Heat& trapezoid, const Heat& bdf2) {
    return Heat{TrBdf2::a * trapezoid.in + bdf2.in, TrBdf2::a * trapezoid.drained + bdf2.drained};
  }
  /// One TR-BDF2 step of size dt from x0 (same regime throughout).
  bool trbdf2(const State& x0, double dt, State& x1, Heat& heat) {
    return stefan1d::tr_bdf2_step(*this, x0, dt, x1, heat);
  }

  // --- construction ---------------------------------------------------------------------------
  SolverOptions opt;

  Impl(const Scenario& scenario, SolverOptions options) : sc(scenario), opt(std::move(options)) {
    const Materials& m = sc.materials;
    geo.m = sc.geometry == Geometry::planar ? 0 : (sc.geometry == Geometry::cylinder ? 1 : 2);
    geo.omega = geo.m == 0 ? 1.0 : (geo.m == 1 ? 2 * std::numbers::pi : 4 * std::numbers::pi);
    water = Phase{m.water_conductivity_w_mk, m.water_heat_capacity(), sc.cells_per_phase};
    ice = Phase{m.ice_conductivity_w_mk, m.ice_heat_capacity(), sc.cells_per_phase};
    THAW_CHECK(water.n >= 3, "at least 3 cells per phase");
    latent = m.latent_heat_per_volume();
    t_m = m.melting_point_c;
    length_scale = sc.outer_radius_m;
    THAW_CHECK(length_scale > 0, "outer radius > 0");
    remnant = kRemnantFraction * length_scale;
    tol = sc.time_tolerance;
    const double u_water = sc.water_initial_temperature_c - t_m;
    const double u_ice = sc.ice_initial_temperature_c - t_m;
    const double u_out = sc.outer_temperature_c - t_m;
    const double u_inner = sc.inner_temperature_c - t_m;
    temperature_scale = std::max({1.0, std::abs(u_water), std::abs(u_ice)});
    if (sc.inner_kind == InnerBoundary::temperature) {
      inner_bc = Bc{BcKind::dirichlet, u_inner, 0};
      temperature_scale = std::max(temperature_scale, std::abs(u_inner));
    }
    switch (sc.outer_kind) {
      case OuterBoundary::temperature:
        outer_bc = Bc{BcKind::dirichlet, u_out, 0};
        temperature_scale = std::max(temperature_scale, std::abs(u_out));
        break;
      case OuterBoundary::convective:
        outer_bc = Bc{BcKind::robin, u_out, sc.heat_transfer_coefficient_w_m2k};
        ablation_heat_flux = sc.heat_transfer_coefficient_w_m2k * u_out;
        temperature_scale = std::max(temperature_scale, std::abs(u_out));
        break;
      case OuterBoundary::flux:
        outer_bc = Bc{BcKind::flux, sc.flux_w_m2, 0};
        ablation_heat_flux = sc.flux_w_m2;
        break;
      case OuterBoundary::insulated:
        outer_bc = Bc{BcKind::flux, 0.0, 0};
        break;
      case OuterBoundary::air:
        outer_bc = Bc{BcKind::air, 0.0, 0};
        air = scenario_air(sc);
        temperature_scale = std::max(temperature_scale, std::abs(u_out));
        break;
    }
    initialise(u_water, u_ice, u_inner);
    if (opt.initial_temperature_c) {
      st.t = opt.start_time_s;
      fill_from_profile(st, [&](double r) { return opt.initial_temperature_c(r) - t_m; });
      e0 = energy(st);
    }
    next_dt = std::min(sc.output_interval_s, sc.duration_s) * 1e-4;
    if (stats.start_time_s > 0) next_dt = std::min(next_dt, 0.25 * stats.start_time_s);
  }

  void initialise(double u_water, double u_ice, double u_inner) {
    const double s0 = sc.inner_radius_m, b0 = sc.outer_radius_m;
    st.t = 0;
    st.s = s0;
    st.b = b0;
    st.liquid = s0 > 0;
    st.ablating = false;
    st.ul.assign(water.n, u_water);
    st.ui.assign(ice.n, u_ice);
    // Energy at t = 0 of the state as given (before any small-time start).
    e0 = latent * geo.w(s0) + water.heat_capacity * u_water * geo.w(s0) +
         ice.heat_capacity * u_ice * (geo.w(b0) - geo.w(s0));
    const double delta = remnant;
    if (!st.liquid && sc.inner_kind == InnerBoundary::temperature && u_inner > 0) {
      // Planar ice block heated on a face, no liquid yet: start from the Neumann melting
      // solution at the time t0 when its front is `delta` from the face.
      const NeumannSolution n =
          solve_neumann(water.k, water.heat_capacity, ice.k, ice.heat_capacity, latent,
                        sc.inner_temperature_c, t_m, sc.ice_initial_temperature_c);
      const double t0 = similarity_start_time(n, delta, ice, b0);
      st.liquid = true;
      st.s = n.front(t0);
      fill_from_profile(st, [&](double r) { return n.temperature(r, t0) - t_m; });
      start_at(t0);
    } else if (st.liquid && b0 - s0 <= 0) {
      // No ice yet. Held cold surface: Neumann freezing from the face r = b0 (planar to
      // O(delta / b0)). Convective / flux cooling of water at T_m: thin ice with a linear
      // profile carrying the surface heat loss (validation guarantees one of these).
      if (outer_bc.kind == BcKind::dirichlet) {
        const NeumannSolution n =
            solve_neumann(ice.k, ice.heat_capacity, water.k, water.heat_capacity, latent,
                          sc.outer_temperature_c, t_m, sc.water_initial_temperature_c);
        const double t0 = similarity_start_time(n, delta, water, b0);
        st.s = b0 - n.front(t0);
        fill_from_profile(st, [&](double r) { return n.temperature(b0 - r, t0) - t_m; });
        start_at(t0);
      } else {
        const double q_out = -arriving_flux(b0);  // heat leaving at T_m [W/m^2], > 0
        THAW_CHECK(q_out > 0 && u_water == 0, "validated zero-ice start");
        double u_surface;
        double q = q_out;
        if (outer_bc.kind == BcKind::robin) {
          u_surface = outer_bc.htc * outer_bc.value / (outer_bc.htc + ice.k / delta);
          q = outer_bc.htc * (u_surface - outer_bc.value);
        } else if (outer_bc.kind == BcKind::air) {
          // the film of ice conducts what the air takes: q_air(u_s) = k u_s / delta
          u_surface = decreasing_root([&](double u) { return air_flux(u, b0) - ice.k * u / delta; },
                                      0.0, 1e-13 * temperature_scale);
          q = -air_flux(u_surface, b0);
        } else {
          u_surface = outer_bc.value * delta / ice.k;
        }
        st.s = b0 - delta;
        fill_from_profile(
            st, [&](double r) { return r <= st.s ? 0.0 : u_surface * (r - st.s) / delta; });
        start_at(latent * delta / q);
      }
    }
    // Ice already at T_m under arriving heat: the surface ablates from the start.
    if (!done && can_ablate() && surface_temperature(st) >= 0) {
      st.ablating = true;
      events.push_back({"melt_onset", st.t, st.b});
    }
  }

  /// When to start a phase of zero initial thickness from the similarity solution n. At the
  /// start the far phase's thermal layer (~2 sqrt(alpha t)) must span about one of its cells:
  /// a layer far thinner than the cells is not resolved, and the heat it should have taken
  /// leaves an dx^2 log(1/dx) error (measured orders 1.6-1.8 when starting at 1e-6 b0 thick).
  /// Starting later is exact in the planar semi-infinite setting; otherwise it neglects
  /// curvature (O(delta/b0) relative, delta ~ one cell: an O(dx^2) front error) and anything the
  /// other boundary does during [0, t0] (t0 ~ dx^2 / alpha, again O(dx^2)). Capped at 5 % of the
  /// output interval and of b0 so coarse grids never start late.
  double similarity_start_time(const NeumannSolution& n, double delta_min, const Phase& far,
                               double b0) const {
    const double dx_far = b0 / far.n;
    const double alpha_far = far.k / far.heat_capacity;
    double t0 = std::max(n.time_of_front(delta_min), dx_far * dx_far / (4 * alpha_far));
    t0 = std::min({t0, 0.05 * sc.output_interval_s, n.time_of_front(0.05 * b0)});
    return std::max(t0, n.time_of_front(delta_min));
  }

  template <class F>
  void fill_from_profile(State& x, F&& u_of_r) {
    // cell averages by 8-point Gauss-Legendre on each cell, weighted by r^m
    static const double xg[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                 0.9602898564975363};
    static const double wg[4] = {0.3626837833783620, 0.3137066524011369, 0.2223810344533745,
                                 0.1012285362903763};
    auto average = [&](double r0, double r1) {
      const double c = 0.5 * (r0 + r1), hw = 0.5 * (r1 - r0);
      double num = 0, den = 0;
      for (int i = 0; i < 4; ++i)
        for (double sgn : {-1.0, 1.0}) {
          const double r = c + sgn * hw * xg[i];
          num += wg[i] * geo.area(r) * u_of_r(r);
          den += wg[i] * geo.area(r);
        }
      return num / den;
    };
    if (x.liquid)
      for (int j = 0; j < water.n; ++j)
        x.ul[j] = average(face_r(0, x.s, water.n, j), face_r(0, x.s, water.n, j + 1));
    const double a = ice_left(x);
    for (int j = 0; j < ice.n; ++j)
      x.ui[j] = average(face_r(a, x.b, ice.n, j), face_r(a, x.b, ice.n, j + 1));
  }

  void start_at(double t0) {
    // The analytic start's heat is booked as the discrete enthalpy it adds (see header).
    st.t = t0;
    stats.start_time_s = t0;
    stats.start_energy_j = geo.omega * (energy(st) - e0);
    heat_in += energy(st) - e0;
  }

  // --- events ---------------------------------------------------------------------------------
  void remove_liquid() {
    // The core has frozen to a remnant of thickness < remnant: map the ice onto [0, b]
    // conservatively (overlap of old and new cells) and book the liquid's enthalpy as removed.
    const double removed = phase_energy(water, 0.0, st.s, st.ul) + latent * geo.w(st.s);
    std::vector<double> energy_new(ice.n, 0.0);
    for (int j = 0; j < ice.n; ++j) {
      const double r0 = face_r(st.s, st.b, ice.n, j), r1 = face_r(st.s, st.b, ice.n, j + 1);
      const double e = ice.heat_capacity * st.ui[j] * (geo.w(r1) - geo.w(r0));
      for (int i = 0; i < ice.n; ++i) {
        const double n0 = face_r(0, st.b, ice.n, i), n1 = face_r(0, st.b, ice.n, i + 1);
        const double lo = std::max(r0, n0), hi = std::min(r1, n1);
        if (hi > lo) energy_new[i] += e * (geo.w(hi) - geo.w(lo)) / (geo.w(r1) - geo.w(r0));
      }
    }
    events.push_back({"core_frozen", st.t, st.s});
    st.liquid = false;
    st.s = 0;
    for (int i = 0; i < ice.n; ++i)
      st.ui[i] = energy_new[i] / (ice.heat_capacity * (geo.w(face_r(0, st.b, ice.n, i + 1)) -
                                                       geo.w(face_r(0, st.b, ice.n, i))));
    stats.removed_energy_j += geo.omega * removed;
    heat_in -= removed;  // booked so that the balance stays exact
  }

  void remove_ice() {
    const double removed = phase_energy(ice, ice_left(st), st.b, st.ui);
    events.push_back({st.liquid ? "break_through" : "fully_melted", st.t, st.liquid ? st.s : 0.0});
    stats.removed_energy_j += geo.omega * removed;
    heat_in -= removed;
    st.b = st.liquid ? st.s : 0.0;
    done = true;
  }

  // --- time stepping ------------------------------------------------------------------------
  struct Trial {
    State x;
    Heat heat;
    double err = 0;
  };

  bool trial(const State& x0, double dt, Trial& out) {
    State full, half, two;
    Heat heat_full, heat_half1, heat_half2;
    if (opt.fixed_step_s > 0) {
      out.err = 0;
      return trbdf2(x0, dt, out.x, out.heat);
    }
    if (!trbdf2(x0, dt, full, heat_full)) return false;
    if (!trbdf2(x0, 0.5 * dt, half, heat_half1)) return false;
    if (!trbdf2(half, 0.5 * dt, two, heat_half2)) return false;
    // Step doubling: for a second-order method the half-step result's error is about
    // (full - two) / (2^2 - 1).
    double err = 0;
    if (two.liquid) err = std::max(err, std::abs(full.s - two.s) / length_scale);
    err = std::max(err, std::abs(full.b - two.b) / length_scale);
    for (std::size_t j = 0; j < two.ui.size(); ++j)
      err = std::max(err, std::abs(full.ui[j] - two.ui[j]) / temperature_scale);
    if (two.liquid)
      for (std::size_t j = 0; j < two.ul.size(); ++j)
        err = std::max(err, std::abs(full.ul[j] - two.ul[j]) / temperature_scale);
    out.x = two;
    out.err = err / 3.0;
    out.heat.in = heat_half1.in + heat_half2.in;
    out.heat.drained = heat_half1.drained + heat_half2.drained;
    return true;
  }

  void accept(const Trial& tr, double dt, bool land_on, double t_target) {
    const double e_before = energy(st);
    st = tr.x;
    if (land_on) st.t = t_target;
    heat_in += tr.heat.in;
    drained += tr.heat.drained;
    const double step_error = std::abs(energy(st) - e_before - (tr.heat.in - tr.heat.drained)) /
                              (latent * geo.w(length_scale));
    stats.max_step_energy_error = std::max(stats.max_step_energy_error, step_error);
    ++stats.steps;
    stats.min_step_s = stats.steps == 1 ? dt : std::min(stats.min_step_s, dt);
    stats.max_step_s = std::max(stats.max_step_s, dt);
  }

  enum class Crossing { none, onset, stop, liquid, ice };

  /// Switches regime at the current state (an event located to within the time floor).
  void fire(Crossing c) {
    if (c == Crossing::onset && !st.ablating) {
      st.ablating = true;
      events.push_back({"melt_onset", st.t, st.b});
    } else if (c == Crossing::stop && st.ablating) {
      st.ablating = false;
      events.push_back({"ablation_stop", st.t, st.b});
    }
  }

  long guard_attempts = 0;   ///< attempted steps in the current guard window
  double guard_start_t = 0;  ///< time at the start of the current guard window [s]

  /// Throws Breakdown when the pace of the last window (simulated time per attempted step)
  /// projects more than kGuardMaxCost to reach the end of the run.
  void guard_runaway() {
    if (opt.fixed_step_s > 0) return;
    const double cost_per_attempt = static_cast<double>(sc.cells_per_phase);
    if (++guard_attempts * cost_per_attempt < kGuardWindowCost) return;
    const double pace_s = (st.t - guard_start_t) / static_cast<double>(guard_attempts);
    const double remaining_s = sc.duration_s - st.t;
    if (pace_s * (kGuardMaxCost / cost_per_attempt) < remaining_s)
      throw Breakdown{"the time step collapsed to " + seconds_text(pace_s) +
                      " on average at t = " + seconds_text(st.t) + " (" +
                      std::to_string(stats.steps) + " steps so far); the run would not end"};
    guard_attempts = 0;
    guard_start_t = st.t;
  }

  double advance_to(double t_target) {
    THAW_CHECK(t_target >= st.t, "advance_to goes forward");
    const double t_floor = 1e-13 * std::max(sc.duration_s, t_target);
    const double tol_u = 1e-9 * temperature_scale;
    int event_retries = 0;
    while (!done && st.t < t_target) {
      guard_runaway();
      double dt = opt.fixed_step_s > 0 ? opt.fixed_step_s : next_dt;
      bool land = false;
      if (st.t + dt >= t_target || t_target - (st.t + dt) < 1e-3 * dt) {
        dt = t_target - st.t;
        land = true;
      }
      Trial tr;
      if (!trial(st, dt, tr)) {
        ++stats.rejected_steps;
        next_dt = 0.25 * dt;
        if (next_dt < t_floor)
          throw Breakdown{"Newton's method did not converge at t = " + seconds_text(st.t) +
                          " even with the step at its floor (" + seconds_text(dt) + ")"};
        continue;
      }
      // Error per step (relative to b0 and the temperature scale). Error per unit step would
      // make the step collapse at the sqrt(t) start of a front from discontinuous data, where
      // the local error shrinks only like sqrt(dt). Local error ~ dt^3 for smooth solutions.
      // Floored at the round-off of the moving grid: swept volumes and cell energies are
      // differences of absolute positions (~b) resolved to eps * b, i.e. eps * b / w relative
      // for a cell of width w. A phase started at a tiny thickness would otherwise demand
      // steps below that noise forever.
      double w_min = (st.b - ice_left(st)) / ice.n;
      if (st.liquid) w_min = std::min(w_min, st.s / water.n);
      const double allowed =
          std::max(tol, 8 * std::numeric_limits<double>::epsilon() * st.b / w_min);
      const double factor = tr.err > 0 ? 0.9 * std::cbrt(allowed / tr.err) : 3.0;
      if (tr.err > allowed && dt > 64 * t_floor) {
        ++stats.rejected_steps;
        next_dt = dt * std::clamp(factor, 0.1, 0.9);
        continue;
      }
      // Event location: the earliest crossing inside the step (linear estimate) shortens it;
      // a step that ends inside the crossing's tolerance band is accepted and fires it.
      const State& x1 = tr.x;
      double shrink = 1.0;
      Crossing which = Crossing::none, fire_after = Crossing::none;
      auto consider = [&](double fraction, Crossing c) {
        if (fraction < shrink) {
          shrink = std::max(fraction, 0.0);
          which = c;
        }
      };
      if (!st.ablating && can_ablate()) {
        const double u0 = surface_temperature(st), u1 = surface_temperature(x1);
        if (u1 > tol_u)
          consider(u0 >= 0 ? 0.0 : -u0 / (u1 - u0), Crossing::onset);
        else if (u1 >= -tol_u)
          fire_after = Crossing::onset;
      }
      if (st.ablating) {
        const double g0 = rates(st).ablation, g1 = rates(x1).ablation;
        const double tol_g = 1e-9 * geo.area(st.b) * std::abs(arriving_flux(st.b));
        if (g1 < -tol_g)
          consider(g0 <= 0 ? 0.0 : g0 / (g0 - g1), Crossing::stop);
        else if (g1 <= tol_g && g0 > tol_g)
          fire_after = Crossing::stop;
      }
      if (x1.liquid && x1.s < 0.5 * remnant && st.s > remnant)
        consider((st.s - 0.75 * remnant) / (st.s - x1.s), Crossing::liquid);
      const double th0 = st.b - ice_left(st), th1 = x1.b - ice_left(x1);
      if (th1 < 0.5 * remnant && th0 > remnant)
        consider((th0 - 0.75 * remnant) / (th0 - th1), Crossing::ice);
      if (which != Crossing::none) {
        if (dt * shrink > t_floor && event_retries < 60) {
          ++stats.rejected_steps;
          ++event_retries;
          next_dt = dt * shrink;
          continue;
        }
        // The crossing is at the current time to within the floor: switch now, step again.
        if (which == Crossing::onset || which == Crossing::stop) {
          fire(which);
          event_retries = 0;
          next_dt = std::max(dt * 1e-3, 64 * t_floor);
          continue;
        }
      }
      event_retries = 0;
      accept(tr, dt, land, t_target);
      fire(fire_after);
      if (st.liquid && st.s < remnant) remove_liquid();
      if (!done && st.b - ice_left(st) < remnant) remove_ice();
      const double next = std::max(dt * std::clamp(factor, 0.2, 3.0), 64 * t_floor);
      next_dt = (land && dt < next_dt) ? std::max(next, std::min(next_dt, 3.0 * dt)) : next;
    }
    return st.t;
  }

  Snapshot snapshot(bool with_profile) const {
    Snapshot out;
    out.time_s = st.t;
    out.inner_radius_m = st.liquid || done ? st.s : 0.0;
    out.outer_radius_m = done ? out.inner_radius_m : st.b;
    out.liquid_volume_m3 = st.liquid ? geo.omega * geo.w(st.s) : 0.0;
    out.ice_volume_m3 = done ? 0.0 : geo.omega * (geo.w(st.b) - geo.w(ice_left(st)));
    const double e = energy_now();
    out.enthalpy_j = geo.omega * e;
    out.heat_in_j = geo.omega * heat_in;
    out.drained_j = geo.omega * drained;
    out.energy_balance_error =
        std::abs(e - e0 - heat_in + drained) / (latent * geo.w(length_scale));
    out.ablating = st.ablating;
    if (!with_profile) return out;
    if (st.liquid) {
      const double dx = st.s / water.n;
      if (inner_bc.kind == BcKind::dirichlet)
        out.profile.push_back({0.0, inner_bc.value + t_m, "water"});
      for (int j = 0; j < water.n; ++j)
        out.profile.push_back({(j + 0.5) * dx, st.ul[j] + t_m, "water"});
      out.profile.push_back({st.s, t_m, "water"});
    }
    if (!done) {
      const double a = ice_left(st), dx = (st.b - a) / ice.n;
      if (st.liquid)
        out.profile.push_back({st.s, t_m, "ice"});
      else if (inner_bc.kind == BcKind::dirichlet)
        out.profile.push_back({0.0, inner_bc.value + t_m, "ice"});
      for (int j = 0; j < ice.n; ++j)
        out.profile.push_back({a + (j + 0.5) * dx, st.ui[j] + t_m, "ice"});
      out.profile.push_back({st.b, surface_temperature(st) + t_m, "ice"});
    }
    return out;
  }

  /// The state at t = 0 exactly as the scenario gives it (before a small-time start).
  Snapshot initial_snapshot(bool with_profile) const {
    Snapshot out;
    const double s0 = sc.inner_radius_m, b0 = sc.outer_radius_m;
    out.inner_radius_m = s0;
    out.outer_radius_m = b0;
    out.liquid_volume_m3 = geo.omega * geo.w(s0);
    out.ice_volume_m3 = geo.omega * (geo.w(b0) - geo.w(s0));
    out.enthalpy_j = geo.omega * e0;
    if (!with_profile) return out;
    const double tw = sc.water_initial_temperature_c, ti = sc.ice_initial_temperature_c;
    if (s0 > 0) {
      if (inner_bc.kind == BcKind::dirichlet)
        out.profile.push_back({0.0, inner_bc.value + t_m, "water"});
      for (int j = 0; j < water.n; ++j)
        out.profile.push_back({(j + 0.5) * s0 / water.n, tw, "water"});
      out.profile.push_back({s0, tw, "water"});
    }
    if (b0 > s0) {
      if (s0 == 0 && inner_bc.kind == BcKind::dirichlet)
        out.profile.push_back({0.0, inner_bc.value + t_m, "ice"});
      for (int j = 0; j < ice.n; ++j)
        out.profile.push_back({s0 + (j + 0.5) * (b0 - s0) / ice.n, ti, "ice"});
      out.profile.push_back(
          {b0, outer_bc.kind == BcKind::dirichlet ? outer_bc.value + t_m : ti, "ice"});
    }
    return out;
  }

  /// Enthalpy of the current state; after the ice is removed only the liquid remains.
  double energy_now() const {
    if (!done) return energy(st);
    return st.liquid ? phase_energy(water, 0.0, st.s, st.ul) + latent * geo.w(st.s) : 0.0;
  }
};

FrontFixingSolver::FrontFixingSolver(const Scenario& scenario, SolverOptions options)
    : m_impl(std::make_unique<Impl>(scenario, std::move(options))) {}
FrontFixingSolver::~FrontFixingSolver() = default;
double FrontFixingSolver::advance_to(double t) {
  try {
    return m_impl->advance_to(t);
  } catch (const Breakdown& b) {
    // A valid scenario the method cannot carry through: the user's to change, so a UserError
    // naming the most extreme key (sim/scenario keeps the ranges), not an internal error.
    const LikelyCause cause = likely_cause_of_solver_failure(m_impl->sc);
    throw UserError(m_impl->sc.source_name, "key '" + cause.key + "'",
                    "the Stefan solver cannot continue: " + b.what + "; " + cause.hint);
  }
}
double FrontFixingSolver::time() const {
  return m_impl->st.t;
}
bool FrontFixingSolver::finished() const {
  return m_impl->done;
}
Snapshot FrontFixingSolver::snapshot(bool with_profile) const {
  return m_impl->snapshot(with_profile);
}
Snapshot FrontFixingSolver::initial_snapshot(bool with_profile) const {
  return m_impl->initial_snapshot(with_profile);
}
const std::vector<Event>& FrontFixingSolver::events() const {
  return m_impl->events;
}
const SolverStatistics& FrontFixingSolver::statistics() const {
  return m_impl->stats;
}
double FrontFixingSolver::reference_energy() const {
  return m_impl->geo.omega * m_impl->latent * m_impl->geo.w(m_impl->length_scale);
}

}  // namespace thaw::sim
