#include "sim/grid/newton_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sim/grid/enthalpy_solver.h"

namespace thaw::sim {

namespace {

/// Newton stops when every cell's balance residual, expressed as a temperature, is below this
/// [K]. Tight enough that mirror-image cells of a symmetric body, whose Newton paths can part
/// where round-off decides on which side of a kink of T(H) a cell lies, still agree far below
/// 1e-9 L_v (tests/sim/grid/test_grid_runs.cpp); it costs about one iteration over 1e-5 K.
constexpr double kNewtonTolerance_K = 1e-7;
constexpr int kMaxNewton = 12;
/// Newton stalling (the residual not halved by an iteration: cells at a kink of T(H) trading
/// places between the melting plateau and a pure phase) is accepted below this residual [K].
constexpr double kStagnantResidual_K = 1e-5;
/// A Newton that has not reached kNewtonTolerance_K in kMaxNewton iterations (it can cycle
/// between the sides of a kink of T(H)) is still accepted below this residual [K]: the final
/// conservative update keeps the energy exact, the residual is only a temperature error.
constexpr double kAcceptableResidual_K = 1e-3;
constexpr int kMaxCg = 5000;
/// A melting cell's Newton update that leaves the plateau stops this far (relative to L_v)
/// past its end: in the new phase, at T_m within L_v kKinkStep / (rho c) ~ 2e-7 K.
constexpr double kKinkStep = 1e-9;
/// A melting cell's update that ends this close (relative to L_v) to an end of the plateau
/// lands on it: the last digits of an enthalpy near a kink are round-off, and its sign decides
/// the cell's phase in the next iteration (mirror-image cells must decide alike).
constexpr double kKinkSnap = 1e-10;

}  // namespace

NewtonSolver::NewtonSolver(const GridMesh& mesh, const PhaseRelation& phase,
                           const ConductionOperator& op, CellState& cells)
    : m_mesh(mesh), m_phase(phase), m_op(op), m_cells(cells) {
  const auto n = static_cast<std::size_t>(mesh.n);
  for (auto* v : {&cg_r, &cg_z, &cg_p, &cg_p2, &cg_q, &dtemp, &diag, &rhs}) v->assign(n, 0.0);
  const auto blocks = static_cast<std::size_t>(mesh.block_count());
  for (auto* v : {&partial_rz, &partial_res, &partial_pq, &partial_newton}) v->assign(blocks, 0.0);
  type.assign(n, kAir);
}

double NewtonSolver::residual(long c, int i, int j, int k) const {
  const CellState& s = m_cells;
  return s.m[c] * m_mesh.vol[c] / dt * (s.H[c] - s.H_start[c]) - m_op.heat_rate(c, i, j, k);
}

/// The conjugate gradients' start on block bl (x = 0, r = rhs, z = r / diag, p = 0) and its
/// partials of r.z and of the residual; done with the Newton residual, which saves a barrier
/// (wasted only when Newton has converged).
void NewtonSolver::start_cg(long bl) {
  double rz = 0, res = 0;
  for (long c = bl * kBlock; c < m_mesh.block_end(bl); ++c) {
    dtemp[c] = 0;
    cg_r[c] = pure(c) ? rhs[c] : 0.0;
    cg_z[c] = pure(c) ? cg_r[c] / diag[c] : 0.0;
    cg_p[c] = 0;  // so that the first fused update gives p = z
    rz += cg_r[c] * cg_z[c];
    res = std::max(res, pure(c) ? std::abs(cg_r[c]) / diag[c] : 0.0);
  }
  partial_rz[static_cast<std::size_t>(bl)] = rz;
  partial_res[static_cast<std::size_t>(bl)] = res;
}

/// Conjugate gradients with a Jacobi preconditioner on the pure cells' temperature changes:
/// (diag_c) x_c - sum K x_nb = b_c. Run by the team's leader; returns iterations.
///
/// Two phases per iteration: the direction update p = z + beta p is fused into the matrix
/// product by double-buffering p (each cell recomputes its neighbours' new p from z and the
/// old p: the same operations, so the same bits). Every reduction goes over fixed blocks whose
/// partials the leader adds in block order, so the result does not depend on the thread
/// count.
bool NewtonSolver::stop_requested() {
  if (!m_stopped && m_stop && *m_stop) m_stopped = (*m_stop)();
  return m_stopped;
}

int NewtonSolver::conjugate_gradients(BlockTeam& team, double tol) {
  std::vector<double>& x = dtemp;
  // x = 0, r = b, z = r / diag, p = 0 and the partials of r.z and of the residual were set by
  // prepare_newton_iteration (start_cg), one phase earlier.
  double rz = ordered_sum(partial_rz), res = largest(partial_res), beta = 0;
  std::vector<double>* po = &cg_p;
  std::vector<double>* pn = &cg_p2;
  for (int it = 0;; ++it) {
    if (res <= tol || rz == 0 || it == kMaxCg || stop_requested()) return it;
    const std::vector<double>& p_old = *po;
    std::vector<double>& p_new = *pn;
    // z and the old p are zero outside the pure cells (start_cg, and p_new below), so the
    // direction there is exactly 0: the same term the product needs from a non-pure neighbour.
    auto direction = [&](long c) { return cg_z[c] + beta * p_old[c]; };
    team.for_blocks([&](long bl) {
      double pq = 0;
      m_mesh.for_cells(bl, [&](long c, int i, int j, int k) {
        if (!pure(c)) {
          p_new[c] = cg_q[c] = 0;
          return;
        }
        const double pc = direction(c);
        p_new[c] = pc;
        cg_q[c] = diag[c] * pc - m_op.neighbour_sum_of(c, i, j, k, direction);
        pq += pc * cg_q[c];
      });
      partial_pq[static_cast<std::size_t>(bl)] = pq;
    });
    const double alpha = rz / ordered_sum(partial_pq);
    team.for_blocks([&](long bl) {
      double rz_b = 0, res_b = 0;
      for (long c = bl * kBlock; c < m_mesh.block_end(bl); ++c) {
        if (!pure(c)) continue;
        x[c] += alpha * p_new[c];
        cg_r[c] -= alpha * cg_q[c];
        cg_z[c] = cg_r[c] / diag[c];
        rz_b += cg_r[c] * cg_z[c];
        res_b = std::max(res_b, std::abs(cg_r[c]) / diag[c]);
      }
      partial_rz[static_cast<std::size_t>(bl)] = rz_b;
      partial_res[static_cast<std::size_t>(bl)] = res_b;
    });
    const double rz_new = ordered_sum(partial_rz);
    res = largest(partial_res);
    beta = rz_new / rz;
    rz = rz_new;
    std::swap(po, pn);
  }
}

/// The previous Newton iteration's update of cell c from the temperature changes dtemp
/// (zero outside the pure cells) and the right-hand side it was solved with.
void NewtonSolver::apply_update(long c, int i, int j, int k) {
  std::vector<double>& H = m_cells.H;
  const double latent = m_phase.latent;
  if (type[c] == kAir) return;
  if (type[c] == kMushy) {
    // dT = 0 here: the cell's own balance gives its enthalpy change, which stops just past
    // the plateau's end if it would leave it (the next iteration then solves the new phase's
    // temperature with its heat capacity). Unclipped, a cell holding little material jumps
    // far into the other phase (its capacity is m V), the next iteration's stop at the kink
    // puts it back on the plateau, and Newton cycles: 72 of the first 134 steps of the hollow
    // cube used all 12 iterations.
    const double next =
        H[c] + (rhs[c] + m_op.neighbour_sum_of(c, i, j, k, [&](long nb) { return dtemp[nb]; })) *
                   dt / (m_cells.m[c] * m_mesh.vol[c]);
    H[c] = std::clamp(next, -kKinkStep * latent, (1 + kKinkStep) * latent);
    if (std::abs(H[c]) <= kKinkSnap * latent) H[c] = 0;
    if (std::abs(H[c] - latent) <= kKinkSnap * latent) H[c] = latent;
  } else if (type[c] == kIce) {
    H[c] = std::min(H[c] + m_phase.ci * dtemp[c], 0.0);  // stop at the kink: melting starts next
  } else {
    H[c] = std::max(H[c] + m_phase.cw * dtemp[c], latent);
  }
}

/// Newton's start for cell c: a pure phase continues its last step's rate of temperature
/// change (stopping at the kink, as an update does); a melting cell starts where it is. Only
/// the start moves, not the solution: it saves about one Newton iteration per step (the
/// first residual is what the rate's change leaves, not the whole step's change).
void NewtonSolver::predict(long c) {
  std::vector<double>& H = m_cells.H;
  const std::vector<double>& rate = m_cells.rate;
  if (m_cells.m[c] == 0 || rate[c] == 0) return;
  if (H[c] < 0) {
    H[c] = std::min(H[c] + m_phase.ci * rate[c] * dt, 0.0);
  } else if (H[c] > m_phase.latent) {
    H[c] = std::max(H[c] + m_phase.cw * rate[c] * dt, m_phase.latent);
  }
}

/// Applies the previous Newton iteration's update (if any), then temperatures, cell types,
/// the CG diagonal and the residual; returns the largest residual as a temperature [K].
/// apply_update reads the neighbours' dtemp, which nothing writes here, and writes only its
/// own H, which the residuals read after the barrier.
double NewtonSolver::prepare_newton_iteration(BlockTeam& team, bool apply) {
  const std::vector<double>& m = m_cells.m;
  const std::vector<double>& H = m_cells.H;
  std::vector<double>& T = m_cells.T;
  team.for_blocks([&](long bl) {
    m_mesh.for_cells(bl, [&](long c, int i, int j, int k) {
      if (apply) {
        apply_update(c, i, j, k);
      } else {
        predict(c);
      }
      T[c] = m[c] > 0 ? m_phase.temperature(H[c]) : 0.0;
    });
  });
  team.for_blocks([&](long bl) {
    double res = 0;
    m_mesh.for_cells(bl, [&](long c, int i, int j, int k) {
      if (m[c] == 0) {
        type[c] = kAir;
        rhs[c] = 0;
        return;
      }
      type[c] = H[c] < 0 ? kIce : (H[c] > m_phase.latent ? kWater : kMushy);
      const double mv = m[c] * m_mesh.vol[c] / dt;
      diag[c] =
          mv * (type[c] == kWater ? m_phase.cw : m_phase.ci) + m_op.conductance_sum(c, i, j, k);
      rhs[c] = -residual(c, i, j, k);
      res = std::max(res, std::abs(rhs[c]) / diag[c]);
    });
    partial_newton[static_cast<std::size_t>(bl)] = res;
    start_cg(bl);
  });
  return largest(partial_newton);
}

NewtonOutcome NewtonSolver::solve(BlockTeam& team, double step_dt, GridStatistics& stats,
                                  const std::function<bool()>& stop) {
  dt = step_dt;
  m_stop = &stop;
  m_stopped = false;
  double best = std::numeric_limits<double>::infinity();
  for (int it = 0; it < kMaxNewton; ++it) {
    if (stop_requested()) return NewtonOutcome::stopped;
    const double res = prepare_newton_iteration(team, it > 0);
    if (res <= kNewtonTolerance_K) return NewtonOutcome::converged;
    if (res <= kStagnantResidual_K && res > 0.5 * best) {
      if (team.leader()) ++stats.stagnant_steps;
      return NewtonOutcome::stagnant;
    }
    best = std::min(best, res);
    if (it + 1 == kMaxNewton) {
      if (res > kAcceptableResidual_K) return NewtonOutcome::unconverged;
      if (team.leader()) ++stats.loose_steps;
      return NewtonOutcome::loose;
    }
    const int cg = conjugate_gradients(team, std::max(1e-3 * res, 0.1 * kNewtonTolerance_K));
    if (team.leader()) {
      ++stats.newton_iterations;
      stats.cell_updates += m_mesh.n;
      stats.cg_iterations += cg;
    }
  }
  return NewtonOutcome::unconverged;
}

}  // namespace thaw::sim
