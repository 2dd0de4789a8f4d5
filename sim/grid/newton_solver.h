#pragma once
// The grid solver's implicit solve of one backward Euler step: a semismooth Newton on the
// enthalpy-temperature relation (Voller & Prakash 1987 with a kink-stopping update). In each
// iteration the cells in a pure phase solve one symmetric positive definite system for their
// temperature change (conjugate gradients, Jacobi preconditioner, the operator's matrix-free
// 7-point stencil); the melting cells then get their enthalpy change from their own balance; an
// update that would cross a kink of T(H) stops at the kink (Newton cannot cycle). Each solver
// has its own convergence test (MFEM ex16: NewtonSolver and CGSolver as objects of their own).
// Writes H and T of the cell state; reads H_start, m and rate. Knows nothing of draining,
// surfaces or step-size control.
#include <functional>
#include <vector>

#include "sim/grid/block_team.h"
#include "sim/grid/cell_state.h"
#include "sim/grid/conduction_operator.h"
#include "sim/grid/grid_mesh.h"
#include "sim/grid/phase_relation.h"

namespace thaw::sim {

struct GridStatistics;

/// How a Newton solve ended.
enum class NewtonOutcome {
  converged,    ///< residual below the tolerance
  stagnant,     ///< stalled at a residual below kStagnantResidual_K: accepted
  loose,        ///< all iterations used, residual below kAcceptableResidual_K: accepted
  unconverged,  ///< not accepted: the step should shrink
  stopped,      ///< `stop` returned true: H is a partial iterate, to be discarded
};

class NewtonSolver {
 public:
  NewtonSolver(const GridMesh& mesh, const PhaseRelation& phase, const ConductionOperator& op,
               CellState& cells);

  /// Solves the backward Euler balance m V / dt (H - H_start) = heat rate(T(H)) for H from the
  /// current H (first moved by `predict`); run by the team's leader. Counts its iterations in
  /// `stats` (newton_iterations, cg_iterations, cell_updates, stagnant_steps, loose_steps).
  /// On return T = T(H) of the last iterate in every material cell. `stop` (if set) is asked
  /// by the leader before each Newton and CG iteration; true ends the solve at once (stopped).
  NewtonOutcome solve(BlockTeam& team, double dt, GridStatistics& stats,
                      const std::function<bool()>& stop = {});

 private:
  enum CellType : unsigned char { kAir = 0, kIce = 1, kWater = 2, kMushy = 3 };
  bool pure(long c) const { return type[c] == kIce || type[c] == kWater; }
  /// Residual of cell c's balance: M/dt (H - H_start) - heat rate [W].
  double residual(long c, int i, int j, int k) const;
  void start_cg(long bl);
  int conjugate_gradients(BlockTeam& team, double tol);
  /// stop() was true once in this solve (stays so).
  bool stop_requested();
  void apply_update(long c, int i, int j, int k);
  void predict(long c);
  double prepare_newton_iteration(BlockTeam& team, bool apply);

  const GridMesh& m_mesh;
  const PhaseRelation& m_phase;
  const ConductionOperator& m_op;
  CellState& m_cells;
  double dt = 0;                                  ///< the step being solved [s]
  const std::function<bool()>* m_stop = nullptr;  ///< this solve's stop request, if any
  bool m_stopped = false;
  std::vector<unsigned char> type;
  std::vector<double> cg_r, cg_z, cg_p, cg_p2, cg_q, dtemp, diag, rhs;
  std::vector<double> partial_rz, partial_res, partial_pq, partial_newton;  ///< per-block partials
};

}  // namespace thaw::sim
