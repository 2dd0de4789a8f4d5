// The Boussinesq MAC solver (flow_solver.h).
#include "sim/flow/flow_solver.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "base/check.h"
#include "sim/flow/multigrid_pressure.h"
#include "sim/flow/ordered_sum.h"

namespace thaw::sim::flow {
namespace {

struct Idx {
  int v[3];
  int& operator[](int d) { return v[d]; }
  int operator[](int d) const { return v[d]; }
};

Idx shifted(Idx a, int d, int by) {
  a[d] += by;
  return a;
}

/// Koren's limited kappa = 1/3 face value: upwind value t_u, far-upwind t_uu, downwind t_d.
double koren_face(double t_uu, double t_u, double t_d) {
  const double up = t_u - t_uu, dn = t_d - t_u;
  if (up * dn <= 0) return t_u;
  const double s = up > 0 ? 1.0 : -1.0;
  const double a = std::abs(up), b = std::abs(dn);
  return t_u + 0.5 * s * std::min({2.0 * b, (a + 2.0 * b) / 3.0, 2.0 * a});
}

/// The implicit conduction's solve: largest residual relative to the right-hand side's largest
/// entry. The final update is conservative whatever the residual, which then only bounds the
/// deviation from the implicit solution (temperatures stay within their bounds to ~1e-12 of
/// the change).
constexpr double kConductionTolerance = 1e-12;

}  // namespace

FlowSolver::FlowSolver(FlowProblem problem, std::unique_ptr<PressureSolver> pressure)
    : problem_(std::move(problem)), pressure_(std::move(pressure)) {
  const MacGrid& g = problem_.grid;
  THAW_CHECK(g.h_m > 0 && g.n[0] >= 2 && g.n[1] >= 2, "flow grid: at least 2 x 2 cells");
  THAW_CHECK(g.dims() == 3 ? g.n[2] >= 2 : g.n[2] == 1, "flow grid: nz is 1 unless 3D");
  if (g.axisymmetric())
    THAW_CHECK(problem_.walls[x_min].kind == WallCondition::Kind::adiabatic,
               "flow: the axis (axisymmetric x_min) carries no heat");
  if (!pressure_) pressure_ = std::make_unique<MultigridPressureSolver>();
  for (int d = 0; d < 3; ++d)
    if (d < g.dims()) velocity_[d].assign(g.face_count(d), 0.0);
  temperature_.assign(g.cell_count(), 0.0);
  parallel_ = g.cell_count() >= 8192;
  operator_drag_dt_ = -1;  // forces the first build
  set_pressure_operator(0);
  psi_.assign(g.cell_count(), 0.0);
  p_.assign(g.cell_count(), 0.0);
  for (int d = 0; d < g.dims(); ++d) {
    viscous_[d] = std::make_unique<MultigridPressureSolver>();
    delta_[d].assign(g.face_count(d), 0.0);
  }
  conduction_ = std::make_unique<MultigridPressureSolver>();
  t_delta_.assign(g.cell_count(), 0.0);
}

FlowSolver::~FlowSolver() = default;

bool FlowSolver::rebuild_coarse(OperatorBuild& build, double dt) {
  // The coarse levels only precondition: rebuilt when the step has moved by a quarter since
  // they were built, and every kCoarseRefresh updates (the drag and nu move with the melt).
  constexpr int kCoarseRefresh = 16;
  const bool rebuild = build.updates < 0 || build.updates >= kCoarseRefresh ||
                       !(dt <= 1.25 * build.dt && dt >= 0.8 * build.dt);
  if (rebuild) {
    build.dt = dt;
    build.updates = 0;
  } else {
    ++build.updates;
  }
  return rebuild;
}

void FlowSolver::set_velocity_m_s(int d, std::vector<double> u) {
  THAW_CHECK(d < problem_.grid.dims() && u.size() == problem_.grid.face_count(d),
             "flow velocity: one value per face");
  velocity_[d] = std::move(u);
}

void FlowSolver::set_drag_per_s(std::vector<double> drag) {
  THAW_CHECK(drag.empty() || drag.size() == problem_.grid.cell_count(),
             "flow drag: one value per cell");
  drag_ = std::move(drag);
  drag_changed_ = true;
  viscous_drag_changed_ = true;
}

bool FlowSolver::update_cell_properties(const std::vector<double>& t) {
  const std::size_t cells = t.size();
  bool changed = nu_.size() != cells;
  nu_.resize(cells);
  buoyancy_.resize(cells);
  for (std::size_t c = 0; c < cells; ++c) {
    const double nu = problem_.fluid.kinematic_viscosity_m2_s(t[c]);
    changed = changed || nu != nu_[c];
    nu_[c] = nu;
    buoyancy_[c] = problem_.fluid.buoyancy_m_s2(t[c]);
  }
  return changed;
}

double FlowSolver::cell_velocity_m_s(int d, int i, int j, int k) const {
  const MacGrid& g = problem_.grid;
  if (d >= g.dims()) return 0;
  Idx a{{i, j, k}};
  Idx b = shifted(a, d, 1);
  return 0.5 *
         (velocity_[d][g.face(d, a[0], a[1], a[2])] + velocity_[d][g.face(d, b[0], b[1], b[2])]);
}

double FlowSolver::stable_time_step_s() const {
  const MacGrid& g = problem_.grid;
  double rate = 0;      // largest sum over axes of |u| / h at a cell
  double momentum = 0;  // largest sum over axes of u^2 / (2 nu) at a cell
  double b_lo = std::numeric_limits<double>::infinity(), b_hi = -b_lo;
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        double s = 0, q = 0;
        for (int d = 0; d < g.dims(); ++d) {
          Idx a{{i, j, k}};
          Idx b = shifted(a, d, 1);
          const double u = std::max(std::abs(velocity_[d][g.face(d, a[0], a[1], a[2])]),
                                    std::abs(velocity_[d][g.face(d, b[0], b[1], b[2])]));
          s += u;
          q += u * u;
        }
        const double t = temperature_[g.cell(i, j, k)];
        rate = std::max(rate, s / g.h_m);
        if (q > 0)
          momentum = std::max(momentum, q / (2 * problem_.fluid.kinematic_viscosity_m2_s(t)));
        const double b = problem_.fluid.buoyancy_m_s2(t);
        b_lo = std::min(b_lo, b);
        b_hi = std::max(b_hi, b);
      }
  for (int w = 0; w < 2 * g.dims(); ++w)  // held walls drive the fluid too
    if (problem_.walls[w].kind == WallCondition::Kind::temperature) {
      const double b = problem_.fluid.buoyancy_m_s2(problem_.walls[w].temperature_c);
      b_lo = std::min(b_lo, b);
      b_hi = std::max(b_hi, b);
    }
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Forward-Euler advection: Courant number (Koren's limiter stays bounded at <= 1/2); the
  // central momentum fluxes with implicit viscosity are stable for dt sum_d u_d^2 <= 2 nu
  // (von Neumann: |1 - i c sin k| <= 1 + 4 d sin^2(k/2) for c^2 <= 2 d, c = u dt / h,
  // d = nu dt / h^2).
  const double dt_advection = rate > 0 ? problem_.courant / rate : kInf;
  const double dt_momentum = momentum > 0 ? 1.0 / momentum : kInf;
  // From rest the spread of the buoyancy (over the cells and the held walls) accelerates the
  // fluid: it moves (b dt^2) at most courant h in a step.
  const double spread = b_hi - b_lo;
  const double dt_buoyancy = spread > 0 ? std::sqrt(problem_.courant * g.h_m / spread) : kInf;
  return std::min({dt_advection, dt_momentum, dt_buoyancy});
}

void FlowSolver::momentum_rhs(const Field& u, const std::vector<double>& t, Field& out) const {
  (void)t;
  const MacGrid& g = problem_.grid;
  const int dims = g.dims();
  const double h = g.h_m;
  const auto& n = g.n;
  // strides of the cells and of each component's faces
  const std::ptrdiff_t sc[3] = {1, n[0], static_cast<std::ptrdiff_t>(n[0]) * n[1]};
  std::ptrdiff_t sf[3][3];
  for (int d = 0; d < 3; ++d) {
    const auto fd = g.face_dims(d);
    sf[d][0] = 1;
    sf[d][1] = fd[0];
    sf[d][2] = static_cast<std::ptrdiff_t>(fd[0]) * fd[1];
  }
  const double* nu = nu_.data();
  for (int d = 0; d < dims; ++d) {
    const auto fd = g.face_dims(d);
    std::vector<double>& o = out[d];
    o.assign(g.face_count(d), 0.0);
    const double* ud = u[d].data();
#pragma omp parallel for collapse(2) schedule(static) if (parallel_)
    for (int k = 0; k < fd[2]; ++k)
      for (int j = 0; j < fd[1]; ++j)
        for (int i = 0; i < fd[0]; ++i) {
          const int f[3] = {i, j, k};
          if (f[d] == 0 || f[d] == n[d]) continue;  // wall faces stay at rest
          const std::ptrdiff_t fi = static_cast<std::ptrdiff_t>(g.face(d, i, j, k));
          const std::ptrdiff_t c_hi = static_cast<std::ptrdiff_t>(g.cell(i, j, k));
          const std::ptrdiff_t c_lo = c_hi - sc[d];
          const double w = d == 0 ? g.radius_at_plane(i) : g.radius_at_centre(i);
          const double u0 = ud[fi - sf[d][d]], u1 = ud[fi], u2 = ud[fi + sf[d][d]];
          // Along d: fluxes at the centres of the cells above (c_hi) and below (c_lo).
          const double ub_hi = 0.5 * (u1 + u2), ub_lo = 0.5 * (u0 + u1);
          const double area_hi = d == 0 ? g.radius_at_centre(i) : w;
          const double area_lo = d == 0 ? g.radius_at_centre(i - 1) : w;
          double sum = area_hi * (-ub_hi * ub_hi + 2.0 * nu[c_hi] * (u2 - u1) / h) -
                       area_lo * (-ub_lo * ub_lo + 2.0 * nu[c_lo] * (u1 - u0) / h);
          // Across e != d: fluxes at the edges (d plane f[d], e plane m), m = f[e] + side; u_d
          // beyond a wall mirrors with a sign flip (no-slip), u_e on the e faces of the cells
          // below (c_lo) and above (c_hi) along d; nu the mean of the edge's cells in the box.
          for (int e = 0; e < dims; ++e) {
            if (e == d) continue;
            const std::ptrdiff_t ef_hi =
                static_cast<std::ptrdiff_t>(g.face(e, i, j, k));  // lower e face of c_hi
            const std::ptrdiff_t ef_lo = ef_hi - sf[e][d];
            const double* ue = u[e].data();
            for (int side = 0; side < 2; ++side) {
              const int m = f[e] + side;
              double ud_lo, ud_hi, nu_sum = nu[c_lo] + nu[c_hi];
              int nu_count = 2;
              if (side == 1) {
                ud_lo = u1;
                ud_hi = m < n[e] ? ud[fi + sf[d][e]] : -u1;
                if (m < n[e]) {
                  nu_sum += nu[c_lo + sc[e]] + nu[c_hi + sc[e]];
                  nu_count = 4;
                }
              } else {
                ud_hi = u1;
                ud_lo = m > 0 ? ud[fi - sf[d][e]] : -u1;
                if (m > 0) {
                  nu_sum += nu[c_lo - sc[e]] + nu[c_hi - sc[e]];
                  nu_count = 4;
                }
              }
              const std::ptrdiff_t off = side == 1 ? sf[e][e] : 0;
              const double ue_lo = ue[ef_lo + off], ue_hi = ue[ef_hi + off];
              const double flux = -0.25 * (ud_lo + ud_hi) * (ue_lo + ue_hi) +
                                  nu_sum / nu_count * ((ud_hi - ud_lo) / h + (ue_hi - ue_lo) / h);
              const double area = e == 0 ? g.radius_at_plane(m) : w;
              sum += (side == 0 ? -1.0 : 1.0) * area * flux;
            }
          }
          double r = sum / (w * h);
          if (d == 0 && g.axisymmetric()) {  // hoop stress: -tau_theta_theta / r = -2 nu u / r^2
            const double nu_f = 0.5 * (nu[c_lo] + nu[c_hi]);
            r -= 2.0 * nu_f * u1 / (w * w);
          }
          if (d == 1) r += 0.5 * (buoyancy_[c_lo] + buoyancy_[c_hi]);
          o[fi] = r;
        }
  }
}

void FlowSolver::temperature_rhs(const Field& u, const std::vector<double>& t, bool advect,
                                 bool diffuse, std::vector<double>& out) const {
  const MacGrid& g = problem_.grid;
  const int dims = g.dims();
  const double h = g.h_m, alpha = problem_.thermal_diffusivity_m2_s;
  const auto& n = g.n;
  const auto& walls = problem_.walls;
  // Temperature of cell a, or of the ghost cell mirrored through the wall it lies beyond
  // (held wall: 2 T_w - T_inside; adiabatic or axis: T_inside), for the far-upwind value.
  auto T = [&](Idx a) {
    for (int e = 0; e < dims; ++e) {
      if (a[e] < 0 || a[e] >= n[e]) {
        const int wall = 2 * e + (a[e] < 0 ? 0 : 1);
        a[e] = a[e] < 0 ? 0 : n[e] - 1;
        const double inside = t[g.cell(a[0], a[1], a[2])];
        return walls[wall].kind == WallCondition::Kind::temperature
                   ? 2.0 * walls[wall].temperature_c - inside
                   : inside;
      }
    }
    return t[g.cell(a[0], a[1], a[2])];
  };
  out.assign(g.cell_count(), 0.0);
#pragma omp parallel for collapse(2) schedule(static) if (parallel_)
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const Idx c{{i, j, k}};
        const double tc = t[g.cell(i, j, k)];
        double sum = 0;
        for (int d = 0; d < dims; ++d)
          for (int side = 0; side < 2; ++side) {
            const Idx f = shifted(c, d, side);  // the face: lower (side 0) or upper
            const double area = d == 0 ? g.radius_at_plane(f[0]) : g.radius_at_centre(i);
            const double sgn = side == 0 ? -1.0 : 1.0;  // outward normal along d
            if (f[d] == 0 || f[d] == n[d]) {
              const WallCondition& w = walls[2 * d + side];
              if (diffuse && w.kind == WallCondition::Kind::temperature)
                sum += area * alpha * (w.temperature_c - tc) / (0.5 * h);
              continue;
            }
            const Idx nb = shifted(c, d, side == 0 ? -1 : 1);
            const double tn = t[g.cell(nb[0], nb[1], nb[2])];
            if (diffuse) sum += area * alpha * (tn - tc) / h;
            if (!advect) continue;
            const double un = u[d][g.face(d, f[0], f[1], f[2])];
            // lower cell of the face and upper cell
            const Idx lo = side == 0 ? nb : c, hi = side == 0 ? c : nb;
            const double t_lo = side == 0 ? tn : tc, t_hi = side == 0 ? tc : tn;
            const double tf = un >= 0 ? koren_face(T(shifted(lo, d, -1)), t_lo, t_hi)
                                      : koren_face(T(shifted(hi, d, 1)), t_hi, t_lo);
            sum -= area * sgn * un * tf;
          }
        out[g.cell(i, j, k)] = sum / (g.radius_at_centre(i) * h);
      }
}

void FlowSolver::advective_transport(const std::vector<double>& q, const std::vector<char>& carries,
                                     std::vector<double>& out) const {
  const MacGrid& g = problem_.grid;
  const int dims = g.dims();
  const auto& n = g.n;
  THAW_CHECK(q.size() == g.cell_count() && carries.size() == g.cell_count(),
             "advective transport: one value per cell");
  auto carrying = [&](const Idx& a) {
    for (int e = 0; e < dims; ++e)
      if (a[e] < 0 || a[e] >= n[e]) return false;
    return carries[g.cell(a[0], a[1], a[2])] != 0;
  };
  out.assign(g.cell_count(), 0.0);
#pragma omp parallel for collapse(2) schedule(static) if (parallel_)
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const Idx c{{i, j, k}};
        if (!carries[g.cell(i, j, k)]) continue;
        double sum = 0;
        for (int d = 0; d < dims; ++d)
          for (int side = 0; side < 2; ++side) {
            const Idx nb = shifted(c, d, side == 0 ? -1 : 1);
            if (!carrying(nb)) continue;
            const Idx f = shifted(c, d, side);
            const double un = velocity_[d][g.face(d, f[0], f[1], f[2])];
            const Idx lo = side == 0 ? nb : c, hi = side == 0 ? c : nb;
            const double q_lo = q[g.cell(lo[0], lo[1], lo[2])],
                         q_hi = q[g.cell(hi[0], hi[1], hi[2])];
            // far-upwind value: the next carrying cell, else the upwind one (first order there)
            double qf;
            if (un >= 0) {
              const Idx uu = shifted(lo, d, -1);
              qf = koren_face(carrying(uu) ? q[g.cell(uu[0], uu[1], uu[2])] : q_lo, q_lo, q_hi);
            } else {
              const Idx uu = shifted(hi, d, 1);
              qf = koren_face(carrying(uu) ? q[g.cell(uu[0], uu[1], uu[2])] : q_hi, q_hi, q_lo);
            }
            const double area = d == 0 ? g.radius_at_plane(f[0]) : g.radius_at_centre(i);
            sum -= (side == 0 ? -1.0 : 1.0) * area * g.unit_area() * un * qf;
          }
        out[g.cell(i, j, k)] = sum;
      }
}

std::array<double, 6> FlowSolver::wall_heat_flows(const std::vector<double>& t) const {
  const MacGrid& g = problem_.grid;
  const double alpha = problem_.thermal_diffusivity_m2_s;
  std::array<double, 6> q{};
  for (int wall = 0; wall < 2 * g.dims(); ++wall) {
    const WallCondition& w = problem_.walls[wall];
    if (w.kind != WallCondition::Kind::temperature) continue;
    const int d = wall / 2;
    const bool upper = wall % 2 == 1;
    double s = 0;
    for (int k = 0; k < g.n[2]; ++k)
      for (int j = 0; j < g.n[1]; ++j)
        for (int i = 0; i < g.n[0]; ++i) {
          const Idx c{{i, j, k}};
          if (c[d] != (upper ? g.n[d] - 1 : 0)) continue;
          const int fx = d == 0 ? (upper ? i + 1 : i) : i;
          s += g.face_area(d, fx) * alpha * (w.temperature_c - t[g.cell(i, j, k)]) / (0.5 * g.h_m);
        }
    q[wall] = s;
  }
  return q;
}

double FlowSolver::wall_heat_flow_k_m3_s(int wall) const {
  return wall_heat_flows(temperature_)[wall];
}

int FlowSolver::project(Field& u, std::vector<double>& psi) {
  const MacGrid& g = problem_.grid;
  const int dims = g.dims();
  const double h = g.h_m;
  std::vector<double> b(g.cell_count());
  double flow_scale = 0;
  for (int d = 0; d < dims; ++d) {
    const auto fd = g.face_dims(d);
    for (int k = 0; k < fd[2]; ++k)
      for (int j = 0; j < fd[1]; ++j)
        for (int i = 0; i < fd[0]; ++i)
          flow_scale = std::max(flow_scale, std::abs(g.face_area(d, i) * u[d][g.face(d, i, j, k)]));
  }
  // b = -(net volume flow out of each cell); the correction below is a grad psi (the implicit
  // drag's share of it).
#pragma omp parallel for collapse(2) schedule(static) if (parallel_)
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        double out = 0;
        for (int d = 0; d < dims; ++d) {
          Idx lo{{i, j, k}};
          Idx hi = shifted(lo, d, 1);
          out += g.face_area(d, hi[0]) * u[d][g.face(d, hi[0], hi[1], hi[2])] -
                 g.face_area(d, lo[0]) * u[d][g.face(d, lo[0], lo[1], lo[2])];
        }
        b[g.cell(i, j, k)] = -out;
      }
  if (flow_scale == 0) return 0;
  const PressureSolveReport report =
      pressure_->solve(b, psi, problem_.pressure_tolerance * flow_scale);
  THAW_CHECK(report.converged, "flow: the pressure solve did not converge");
  // u_f -= a_f (psi_upper - psi_lower) / h on faces between two cells.
  for (int d = 0; d < dims; ++d) {
    const auto fd = g.face_dims(d);
#pragma omp parallel for collapse(2) schedule(static) if (parallel_)
    for (int k = 0; k < fd[2]; ++k)
      for (int j = 0; j < fd[1]; ++j)
        for (int i = 0; i < fd[0]; ++i) {
          const Idx f{{i, j, k}};
          if (f[d] == 0 || f[d] == g.n[d]) continue;
          const Idx lo = shifted(f, d, -1);
          const std::size_t fi = g.face(d, i, j, k);
          const double a = face_factor_[0].empty() ? 1.0 : face_factor_[d][fi];
          u[d][fi] -= a * (psi[g.cell(i, j, k)] - psi[g.cell(lo[0], lo[1], lo[2])]) / h;
        }
  }
  return report.iterations;
}

void FlowSolver::set_pressure_operator(double drag_dt) {
  const MacGrid& g = problem_.grid;
  if (drag_.empty()) {
    for (auto& f : face_factor_) f.clear();
    if (operator_drag_dt_ == 0) return;
  } else if (drag_dt == operator_drag_dt_ && !drag_changed_) {
    return;
  }
  // g_f = a_f A_f / h on faces between two cells, 0 on walls; a_f = 1 / (1 + dt D_f) with D_f the
  // mean drag of the face's two cells: the implicit drag's share of the pressure gradient.
  std::array<std::vector<double>, 3> cond;
  for (int d = 0; d < 3; ++d) {
    cond[d].assign(g.face_count(d), 0.0);
    if (d >= g.dims()) continue;
    if (!drag_.empty()) face_factor_[d].assign(g.face_count(d), 1.0);
    const auto f = g.face_dims(d);
    for (int k = 0; k < f[2]; ++k)
      for (int j = 0; j < f[1]; ++j)
        for (int i = 0; i < f[0]; ++i) {
          const Idx a{{i, j, k}};
          if (a[d] == 0 || a[d] == g.n[d]) continue;
          double factor = 1;
          if (!drag_.empty()) {
            const Idx lo = shifted(a, d, -1);
            factor =
                1.0 / (1.0 + drag_dt * 0.5 *
                                 (drag_[g.cell(i, j, k)] + drag_[g.cell(lo[0], lo[1], lo[2])]));
            face_factor_[d][g.face(d, i, j, k)] = factor;
          }
          cond[d][g.face(d, i, j, k)] = factor * g.face_area(d, i) / g.h_m;
        }
  }
  if (rebuild_coarse(pressure_built_, drag_dt))
    pressure_->set_operator(g.n, cond);
  else
    pressure_->update_operator(g.n, cond);
  operator_drag_dt_ = drag_.empty() ? 0 : drag_dt;
  drag_changed_ = false;
}

int FlowSolver::momentum_predictor(double dt, bool nu_changed) {
  const MacGrid& g = problem_.grid;
  const int dims = g.dims();
  const double h = g.h_m;
  const auto& n = g.n;
  auto nu_at = [&](const Idx& c) { return nu_[g.cell(c[0], c[1], c[2])]; };
  auto drag_at = [&](const Idx& c) {
    return drag_.empty() ? 0.0 : drag_[g.cell(c[0], c[1], c[2])];
  };
  // Index of the face along e of node f in the box of nodes fd (the face grid of d).
  auto node_face = [](const std::array<int, 3>& fd, int e, const Idx& f) {
    std::array<int, 3> m = fd;
    ++m[e];
    return static_cast<std::size_t>(f[0]) +
           static_cast<std::size_t>(m[0]) *
               (static_cast<std::size_t>(f[1]) + static_cast<std::size_t>(m[1]) * f[2]);
  };
  // Face "volume" (reduced: radius weight x h, the common h^(dims-1) dropped as in momentum_rhs).
  auto weight = [&](int d, int i) { return d == 0 ? g.radius_at_plane(i) : g.radius_at_centre(i); };
  // nu at the edge between node f and node f + e_e (d plane f[d], e plane m): the mean over the
  // up to 4 cells around it inside the box, as momentum_rhs.
  auto nu_edge = [&](int d, int e, const Idx& f, int m) {
    double sum = 0;
    int count = 0;
    for (int a = -1; a <= 0; ++a)
      for (int b = -1; b <= 0; ++b) {
        Idx c = f;
        c[d] += a;
        c[e] = m + b;
        if (c[e] < 0 || c[e] >= n[e]) continue;
        sum += nu_at(c);
        ++count;
      }
    return sum / count;
  };
  if (nu_changed || dt != viscous_dt_ || viscous_drag_changed_) {
    // (V (1 + dt D) + dt V hoop) delta + dt sum_f nu A / h (delta - delta_nb): the no-slip walls
    // along the face (mirrored ghost: -delta) and the wall faces themselves (delta = 0) enter
    // the diagonal; wall-face nodes are decoupled (mass 1, right-hand side 0).
    for (int d = 0; d < dims; ++d) {
      const auto fd = g.face_dims(d);
      std::array<std::vector<double>, 3> cond;
      for (int e = 0; e < 3; ++e) {
        std::array<int, 3> m = fd;
        ++m[e];
        cond[e].assign(static_cast<std::size_t>(m[0]) * m[1] * m[2], 0.0);
      }
      std::vector<double> mass(g.face_count(d), 0.0);
      for (int k = 0; k < fd[2]; ++k)
        for (int j = 0; j < fd[1]; ++j)
          for (int i = 0; i < fd[0]; ++i) {
            const Idx f{{i, j, k}};
            const std::size_t fi = g.face(d, i, j, k);
            if (f[d] == 0 || f[d] == n[d]) {
              mass[fi] = 1;
              continue;
            }
            const Idx lo = shifted(f, d, -1);
            const double w = weight(d, i), volume = w * h;
            double m = volume * (1 + dt * 0.5 * (drag_at(lo) + drag_at(f)));
            if (d == 0 && g.axisymmetric())  // hoop stress 2 nu u / r^2
              m += dt * 2 * 0.5 * (nu_at(lo) + nu_at(f)) * volume / (w * w);
            // along d, through the cells above (f) and below (lo)
            const double area_hi = d == 0 ? g.radius_at_centre(f[0]) : w;
            const double area_lo = d == 0 ? g.radius_at_centre(lo[0]) : w;
            const double g_hi = dt * nu_at(f) * area_hi / h, g_lo = dt * nu_at(lo) * area_lo / h;
            if (f[d] + 1 == n[d])
              m += g_hi;
            else
              cond[d][node_face(fd, d, shifted(f, d, 1))] = g_hi;
            if (f[d] - 1 == 0) m += g_lo;
            // across e != d, through the edges at e planes f[e] (below) and f[e] + 1 (above)
            for (int e = 0; e < dims; ++e) {
              if (e == d) continue;
              for (int side = 0; side < 2; ++side) {
                const int plane = f[e] + side;
                const double area = e == 0 ? g.radius_at_plane(plane) : w;
                const double c = dt * nu_edge(d, e, f, plane) * area / h;
                if (plane == 0 || plane == n[e])
                  m += 2 * c;  // no-slip: the ghost mirrors -delta
                else if (side == 1)
                  cond[e][node_face(fd, e, shifted(f, e, 1))] = c;
              }
            }
            mass[fi] = m;
          }
      if (d == 0 ? rebuild_coarse(viscous_built_, dt) : viscous_built_.updates == 0)
        viscous_[d]->set_operator(fd, cond, mass);
      else
        viscous_[d]->update_operator(fd, cond, mass);
    }
    viscous_dt_ = dt;
    viscous_drag_changed_ = false;
  }
  int iterations = 0;
  std::vector<double> b;
  for (int d = 0; d < dims; ++d) {
    const auto fd = g.face_dims(d);
    b.assign(g.face_count(d), 0.0);
    double b_max = 0;
    for (int k = 0; k < fd[2]; ++k)
      for (int j = 0; j < fd[1]; ++j)
        for (int i = 0; i < fd[0]; ++i) {
          const Idx f{{i, j, k}};
          if (f[d] == 0 || f[d] == n[d]) continue;
          const Idx lo = shifted(f, d, -1);
          const std::size_t fi = g.face(d, i, j, k);
          const double grad_p = (p_[g.cell(i, j, k)] - p_[g.cell(lo[0], lo[1], lo[2])]) / h;
          const double drag = 0.5 * (drag_at(lo) + drag_at(f));
          b[fi] = dt * weight(d, i) * h * (rhs_[d][fi] - grad_p - drag * velocity_[d][fi]);
          b_max = std::max(b_max, std::abs(b[fi]));
        }
    std::vector<double>& delta = delta_[d];
    if (b_max == 0) {
      std::fill(delta.begin(), delta.end(), 0.0);
      continue;
    }
    const PressureSolveReport r = viscous_[d]->solve(b, delta, problem_.implicit_tolerance * b_max);
    THAW_CHECK(r.converged, "flow: the implicit viscous solve did not converge");
    iterations += r.iterations;
    std::vector<double>& u = velocity_[d];
    for (std::size_t f = 0; f < u.size(); ++f) u[f] += delta[f];
  }
  return iterations;
}

int FlowSolver::conduct(double dt, FlowStepReport& report) {
  const MacGrid& g = problem_.grid;
  const int dims = g.dims();
  const double h = g.h_m, alpha = problem_.thermal_diffusivity_m2_s;
  const auto& n = g.n;
  const auto& walls = problem_.walls;
  std::vector<double>& t = temperature_;
  // T* = T^n + dt (advection of T^n by u^n), held in t_rhs_ by step().
  for (std::size_t c = 0; c < t.size(); ++c) t[c] += dt * t_rhs_[c];
  if (dt != conduction_dt_) {
    // (V + dt sum_f alpha A / h) delta - ...: held walls at half a cell in the diagonal.
    std::array<std::vector<double>, 3> cond;
    for (int d = 0; d < 3; ++d) cond[d].assign(g.face_count(d), 0.0);
    std::vector<double> mass(g.cell_count());
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) {
          const Idx c{{i, j, k}};
          double m = g.radius_at_centre(i) * h;
          for (int d = 0; d < dims; ++d)
            for (int side = 0; side < 2; ++side) {
              const Idx f = shifted(c, d, side);
              const double area = d == 0 ? g.radius_at_plane(f[0]) : g.radius_at_centre(i);
              if (f[d] == 0 || f[d] == n[d]) {
                if (walls[2 * d + side].kind == WallCondition::Kind::temperature)
                  m += dt * alpha * area / (0.5 * h);
              } else if (side == 1) {
                cond[d][g.face(d, f[0], f[1], f[2])] = dt * alpha * area / h;
              }
            }
          mass[g.cell(i, j, k)] = m;
        }
    conduction_->set_operator(n, cond, mass);
    conduction_dt_ = dt;
  }
  std::vector<double> diffusion, b(t.size());
  temperature_rhs(velocity_, t, false, true, diffusion);
  double b_max = 0;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const std::size_t c = g.cell(i, j, k);
        b[c] = dt * g.radius_at_centre(i) * h * diffusion[c];
        b_max = std::max(b_max, std::abs(b[c]));
      }
  int iterations = 0;
  std::vector<double> t_solved = t;
  if (b_max > 0) {
    const PressureSolveReport r = conduction_->solve(b, t_delta_, kConductionTolerance * b_max);
    THAW_CHECK(r.converged, "flow: the implicit conduction solve did not converge");
    iterations = r.iterations;
    for (std::size_t c = 0; c < t.size(); ++c) t_solved[c] += t_delta_[c];
  }
  // The conservative final update: the fluxes of the solved temperatures telescope, so
  // integral T dV changes by exactly the wall heat whatever the solve's residual.
  temperature_rhs(velocity_, t_solved, false, true, diffusion);
  for (std::size_t c = 0; c < t.size(); ++c) t[c] += dt * diffusion[c];
  const std::array<double, 6> q = wall_heat_flows(t_solved);
  for (int w = 0; w < 6; ++w) report.wall_heat_k_m3 += dt * q[w];
  return iterations;
}

FlowStepReport FlowSolver::step(double dt) {
  FlowStepReport report;
  report.dt_s = dt;
  const bool nu_changed = update_cell_properties(temperature_);
  momentum_rhs(velocity_, temperature_, rhs_);
  if (!hold_temperature_) temperature_rhs(velocity_, temperature_, true, false, t_rhs_);
  set_pressure_operator(dt);
  // The pressure that balances the explicit forces: a R - a grad p divergence-free (warm
  // started from the last step's). A fluid in hydrostatic balance then stays at rest, and the
  // implicit viscous step sees only the forces that move the fluid.
  for (int d = 0; d < problem_.grid.dims(); ++d) {
    forces_[d] = rhs_[d];
    if (!face_factor_[d].empty())
      for (std::size_t f = 0; f < forces_[d].size(); ++f) forces_[d][f] *= face_factor_[d][f];
  }
  report.pressure_iterations += project(forces_, p_);
  implicit_iterations_ += momentum_predictor(dt, nu_changed);
  report.pressure_iterations += project(velocity_, psi_);
  if (!hold_temperature_) implicit_iterations_ += conduct(dt, report);
  time_s_ += dt;
  return report;
}

double FlowSolver::thermal_content_k_m3() const {
  const MacGrid& g = problem_.grid;
  return ordered_row_sum(g.n[1], g.n[2], [&](int j, int k) {
    double s = 0;
    for (int i = 0; i < g.n[0]; ++i) s += g.cell_volume(i) * temperature_[g.cell(i, j, k)];
    return s;
  });
}

double FlowSolver::max_divergence_per_s() const {
  const MacGrid& g = problem_.grid;
  double m = 0;
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        double out = 0;
        for (int d = 0; d < g.dims(); ++d) {
          Idx lo{{i, j, k}};
          Idx hi = shifted(lo, d, 1);
          out += g.face_area(d, hi[0]) * velocity_[d][g.face(d, hi[0], hi[1], hi[2])] -
                 g.face_area(d, lo[0]) * velocity_[d][g.face(d, lo[0], lo[1], lo[2])];
        }
        m = std::max(m, std::abs(out) / g.cell_volume(i));
      }
  return m;
}

double FlowSolver::max_speed_m_s() const {
  const MacGrid& g = problem_.grid;
  double m = 0;
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        double s = 0;
        for (int d = 0; d < g.dims(); ++d) s += std::pow(cell_velocity_m_s(d, i, j, k), 2);
        m = std::max(m, std::sqrt(s));
      }
  return m;
}

}  // namespace thaw::sim::flow
