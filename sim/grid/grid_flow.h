#pragma once
// Natural convection in the grid solver's water (issue 24): a Boussinesq flow solver
// (sim/flow/flow_solver.h) on the grid solver's own cells, coupled by operator splitting. After
// each accepted enthalpy step the flow advances over it (as many stable sub-steps as it needs) with
// the buoyancy of the step's end temperatures (the next step's start), the ice and the air held
// still by enthalpy-porosity: a Carman-Kozeny drag C (1 - phi)^2 / (phi^3 + e) on the cell's liquid
// volume fraction phi (Voller & Prakash 1987; Brent, Voller & Reid 1988: C = 1.6e6 kg/(m^3 s) over
// rho_0, e = 1e-3). The flow's velocities then carry the water's sensible heat c_w (T - T_m)
// between material cells in the next step (Koren-limited upwind, at that step's start
// temperatures): a heat rate per cell that the conduction operator adds to its balance, so the step
// stays implicit in conduction and explicit in advection, and the advective rates sum to zero (the
// energy books are unchanged). The step is limited by the flow's Courant number. The flow runs on a
// box of the grid's cells around the water (every cell at least half liquid and not exposed to the
// outside air, whose melt drains away, and a cell more, with a margin of kBoxMargin cells when the
// box moves; axisymmetric: from the axis): the cells outside it are ice or air, which the drag
// would hold still anyway. The box grows (and shrinks) with the liquid, the velocities carried
// over. Reads the cell state; writes only the advected heat rates. Knows nothing of files.
#include <array>
#include <memory>
#include <vector>

#include "sim/flow/flow_solver.h"
#include "sim/grid/cell_state.h"
#include "sim/grid/grid_mesh.h"
#include "sim/grid/grid_problem.h"
#include "sim/grid/phase_relation.h"

namespace thaw::sim {

class GridFlow {
 public:
  /// exposed: cells open to the outside air or next to it (CavityDrain::exposed()); the melt
  /// there drains away, so only the liquid elsewhere sizes the box.
  GridFlow(const GridMesh& mesh, const PhaseRelation& phase, const GridProblem& problem,
           const CellState& cells, const std::vector<char>& exposed);
  ~GridFlow();

  /// Advances the flow over dt with the current state (H, m) and sets advected_w() for the next
  /// step (zero before the first advance: the water starts at rest).
  void advance(double dt);
  /// Advected heat rate into each cell [W]; sums to zero over the cells.
  const std::vector<double>& advected_w() const { return m_advected_w; }
  /// Largest step the explicit advection allows at the current velocities [s] (infinite at rest).
  double max_step_s() const;
  /// Largest speed [m/s] at a cell centre.
  double max_speed_m_s() const { return m_flow ? m_flow->max_speed_m_s() : 0.0; }
  /// Velocity component d [m/s] at the centre of the grid's cell (i, j, k) (0 outside the box).
  double cell_velocity_m_s(int d, int i, int j, int k) const;
  /// The flow's box: first cell and cells per axis, in the grid's indices.
  const std::array<int, 3>& box_first_cell() const { return m_lo; }
  const std::array<int, 3>& box_cells() const { return m_n; }
  long flow_steps() const { return m_flow_steps; }
  /// Sum over the flow's steps of its box's cells.
  double flow_cell_steps() const { return m_flow_cell_steps; }
  /// Rayleigh number of the liquid now: g (rho_max - rho_min) / rho_0 D^3 / (nu alpha), the
  /// density spread over [T_m, the warmest mostly liquid cell] (the ice holds T_m), D the
  /// diameter of the sphere of the liquid's volume, nu at the liquid's mean temperature,
  /// alpha = k_w / (rho c)_w.
  double rayleigh() const;

 private:
  const GridMesh& m_mesh;
  const PhaseRelation& m_phase;
  const GridProblem& m_problem;
  const CellState& m_cells;
  const std::vector<char>& m_exposed;
  /// Fits the box to the cells holding liquid (false: none holds any; the flow is dropped).
  bool fit_box();
  std::array<int, 3> m_lo{0, 0, 0}, m_n{0, 0, 0};
  std::unique_ptr<flow::FlowSolver> m_flow;  ///< on the box; null while no cell holds liquid
  std::vector<double> m_advected_w;          ///< grid cells
  std::vector<double> m_drag, m_sensible, m_advected_box;  ///< box cells
  std::vector<char> m_carries;
  long m_flow_steps = 0;
  double m_flow_cell_steps = 0;
};

}  // namespace thaw::sim
