#pragma once
// The grid solver's time stepper: backward Euler steps of adaptive size (or fixed, for
// validation) to each requested time, with step rejection when Newton fails, the conservative
// final update (the discrete total enthalpy changes by exactly the boundary heat), draining,
// the energy books and the events (melt onset, break-through, core frozen, fully melted). The
// steps run in one OpenMP parallel region: the leader runs the control flow and posts each
// phase, the other threads help with its blocks (block_team.h). As MFEM ex16's ODESolver, it
// drives the parts and owns none of their physics: the operator (conduction_operator.h), the
// implicit solve (newton_solver.h), the surface areas (surface_area.h), cavities and drainage
// (cavity_drain.h). Knows nothing of files or TOML.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "sim/grid/block_team.h"
#include "sim/grid/body_faces.h"
#include "sim/grid/cavity_drain.h"
#include "sim/grid/cell_state.h"
#include "sim/grid/conduction_operator.h"
#include "sim/grid/enthalpy_solver.h"
#include "sim/grid/grid_flow.h"
#include "sim/grid/grid_mesh.h"
#include "sim/grid/grid_problem.h"
#include "sim/grid/newton_solver.h"
#include "sim/grid/phase_relation.h"
#include "sim/grid/surface_area.h"

namespace thaw::sim {

class GridTimeStepper {
 public:
  /// Classifies the initial openness and surface areas and books the initial energy.
  GridTimeStepper(const GridProblem& problem, const GridMesh& mesh, const PhaseRelation& phase,
                  CellState& cells, CavityDrain& cavity, SurfaceArea& surface,
                  ConductionOperator& op, NewtonSolver& newton, GridFlow* flow = nullptr);

  /// Advances to exactly target (> time()) or until no ice is left; returns the time reached.
  /// `stop` (if set) is asked between steps and between Newton and CG iterations (a few
  /// milliseconds apart on any grid the rules accept); once it returns true, the step under way
  /// is discarded and the time reached returned, short of target (the state and the statistics
  /// are those of the last accepted step: without flow, advancing again continues as if never
  /// stopped). Throws GridRunaway (after leaving the parallel region) when the run would not end.
  double advance_to(double target, const std::function<bool()>& stop = {});

  double time() const { return m_time; }
  bool done() const { return m_done; }
  const std::vector<GridEvent>& events() const { return m_events; }
  const GridStatistics& statistics() const { return m_stats; }
  /// Latent heat of all initial material [J].
  double reference_energy() const { return m_reference; }
  double initial_energy() const { return m_e0; }
  double heat_in() const { return m_heat_in; }
  /// heat_in() by the body's face (body_face_names(GridProblem::face_shape)) [J].
  const std::vector<double>& face_heat_in() const { return m_face_heat_in; }
  double drained() const { return m_drained; }
  /// Material volume drained so far [m^3] (melt and held water spilt; the solver's one
  /// density: docs/simulate.md, "Water held in an open shell").
  double drained_volume() const { return m_drained_m3; }
  /// Total enthalpy of the material [J].
  double energy() const;

 private:
  /// One block's share of a step's sums and maxima, written in one phase and read by the
  /// leader after it, which adds the blocks' shares in block order: the same bits for any
  /// thread count.
  struct BlockSums {
    double energy_start = 0, heat = 0, energy_end = 0, ice = 0, dtemp = 0, dmelt = 0;
    FaceWeights face_heat{};  ///< heat by body face
    double drained_m3 = 0;    ///< material volume drained
    DrainTally drain;
    EnclosedTally enclosed;
  };
  template <class G>
  double sum_blocks(G&& g) const {
    double total = 0;
    for (const BlockSums& b : m_block_sums) total += g(b);
    return total;
  }
  template <class G>
  double max_blocks(G&& g) const {
    double most = 0;
    for (const BlockSums& b : m_block_sums) most = std::max(most, g(b));
    return most;
  }
  enum class StepResult { accepted, rejected, stopped };
  StepResult step(BlockTeam& team, const std::function<bool()>& stop);
  /// The runaway guard, before each attempted step (leader): a message if the run would not
  /// end at the pace of the last window of work.
  std::string runaway(double target);
  void end_of_step(double step_dt, double saved);
  void record_openings();
  void advance_team(BlockTeam& team, double target, const std::function<bool()>& stop);

  const GridProblem& p;
  const GridMesh& m_mesh;
  const PhaseRelation& m_phase;
  CellState& m_cells;
  CavityDrain& m_cavity;
  SurfaceArea& m_surface;
  ConductionOperator& m_op;
  NewtonSolver& m_newton;
  GridFlow* m_flow;  ///< natural convection, or nullptr

  std::vector<BlockSums> m_block_sums;
  double m_time = 0;
  double dt = 0;                               ///< the step being taken [s]
  double dt_next = 0;                          ///< the next step's size [s]
  double step_remaining = 0, step_target = 0;  ///< for landing exactly on the target time
  bool m_done = false, melt_started = false, core_frozen = false;
  bool had_enclosed_liquid = false;
  long last_liquid_cell = 0;
  double m_e0 = 0, m_heat_in = 0, m_drained = 0, m_reference = 0, initial_material = 0;
  std::vector<double> m_face_heat_in;
  double m_drained_m3 = 0;
  /// The most ice the body has held [m^3] (a body all water at first has none to lose).
  double m_most_ice = 0;
  std::vector<GridEvent> m_events;
  GridStatistics m_stats;
  long m_attempts = 0;              ///< attempted steps (accepted and rejected)
  double m_guard_cost = 0;          ///< work at the start of the guard's window [cell steps]
  double m_guard_time_s = 0;        ///< simulated time at the start of the guard's window
  double m_last_window_step_s = 0;  ///< mean step over the guard's last window [s]
  std::string m_runaway;            ///< the guard's message (advance_to throws it)
};

}  // namespace thaw::sim
