#pragma once
// The axisymmetric / 3D two-phase Stefan solver: a fixed-grid enthalpy method (Voller & Prakash
// 1987; Voller 1985) on uniform cubic cells. This class is the face; the parts, each in a file
// of its own (MFEM ex16's shape: operator, solvers and stepper as separate objects):
//  * grid_mesh.h, phase_relation.h, cell_state.h: the cells, T(H) and the per-cell state.
//    Unknown: enthalpy H per unit volume of material in each cell (H means nothing else in
//    sim/grid); T(H) is piecewise linear (ice, melting plateau at T_m, water), so the front is
//    where the liquid fraction H / L crosses one half.
//  * conduction_operator.h: the face conductances, with the front reconstructed below the cell
//    size from the liquid fraction (between a melting cell and a neighbour in a pure phase the
//    front, at T_m, is placed inside the melting cell by its fraction of that phase; observed
//    order of the front 1.6 instead of the plain method's 1.0), and the boundary terms.
//  * newton_solver.h: backward Euler in time with a semismooth Newton on the enthalpy-
//    temperature relation; the pure cells' temperature change by conjugate gradients (Jacobi,
//    matrix-free 7-point stencil), the melting cells' enthalpy from their own balance; an
//    update that would cross a kink of T(H) stops at the kink (Newton cannot cycle).
//  * grid_time_stepper.h: step sizes and rejection; after Newton, each cell's enthalpy is set
//    from its conservative balance at the final temperatures, so the discrete total enthalpy
//    changes by exactly the boundary heat (to round-off) whatever the Newton tolerance.
//  * cavity_drain.h: melt drains from cells open to the outside air (connected through cells
//    less than half ice to the grid's air border), and their neighbours (its enthalpy is
//    booked as drained); a shrinking ice fraction is ablation. An enclosed cavity joining the
//    outside is a break-through; an enclosed liquid freezing away is core_frozen.
//  * surface_area.h: the material | air surface area in each cell from the gradient of the
//    material fraction (|grad m| V, the mean of Youngs' and the plain central differences), so
//    the heated area of a round body is not the stair-step area of its cells.
// The steps run in one OpenMP parallel region: a leader runs the control flow and posts each
// phase, the other threads help with its blocks (block_team.h). Deterministic for any thread
// count: every loop writes its own cells, and every sum goes over fixed blocks in a fixed order.
// Knows nothing of files, TOML or shapes.
#include <array>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "sim/grid/grid_field.h"
#include "sim/grid/grid_problem.h"

namespace thaw::sim {

/// A change of regime with where it happened.
struct GridEvent {
  /// "melt_onset" | "break_through" | "water_level_drop" | "core_frozen" | "fully_melted"
  std::string kind;
  double time_s = 0;
  std::array<double, 3> position_m{0, 0, 0};  ///< cell centre (axisymmetric: {r, y, 0})
};

struct GridStatistics {
  long steps = 0, rejected_steps = 0, newton_iterations = 0, cg_iterations = 0;
  double min_step_s = 0, max_step_s = 0;
  double max_step_energy_error = 0;  ///< max over steps of |dE - heat + drained| / reference
  long long cell_updates = 0;        ///< cells x Newton iterations
  long flow_steps = 0;               ///< steps of the water's flow solver ([simulation] flow)
  double flow_cell_steps = 0;        ///< sum over the flow's steps of the cells of its box
  long loose_steps = 0;  ///< steps accepted after 12 Newton iterations, residual in (1e-7, 1e-3] K
  long stagnant_steps = 0;     ///< steps whose Newton stalled at a residual in (1e-7, 1e-5] K
  long unconverged_steps = 0;  ///< steps accepted at the smallest step without Newton convergence
  double removed_ice_m3 =
      0;  ///< ice remnants (< 0.1 % of a cell, at T_m) removed with drained melt
};

/// The integrated state at one instant (volumes of the whole body: full revolution for
/// axisymmetric grids).
struct GridSnapshot {
  double time_s = 0;
  double liquid_volume_m3 = 0, ice_volume_m3 = 0;
  double enclosed_liquid_volume_m3 = 0;  ///< liquid not open to the outside (or held)
  /// Water held in opened cavities (cups) [m^3], their lowest free surface [m] (y; +infinity:
  /// none), and the material volume drained so far [m^3]. The solver has one density for ice
  /// and water: ice + liquid + drained = the initial material volume (docs/simulate.md).
  double held_water_m3 = 0, water_level_m = 0, drained_m3 = 0;
  double enthalpy_j = 0, heat_in_j = 0, drained_j = 0;
  double energy_balance_error = 0;  ///< |E - E0 - heat_in + drained| / reference energy
  /// heat_in_j by the body's face (EnthalpySolver::face_names) [J]
  std::vector<double> face_heat_in_j;
  /// With natural convection ([simulation] flow): the largest speed [m/s] at a cell centre and
  /// the liquid's Rayleigh number (GridFlow::rayleigh); 0 without.
  double max_speed_m_s = 0, rayleigh = 0;
};

/// A run that would not end: at the pace of its last stretch of work (simulated time per cell
/// step) the rest of the run would cost more than kGuardMaxCellSteps. Thrown by advance_to
/// outside its parallel region; the caller names the scenario key (sim/simulate.cpp).
class GridRunaway : public std::runtime_error {
 public:
  GridRunaway(const std::string& what, bool at_max_step)
      : std::runtime_error(what), at_max_step(at_max_step) {}
  /// The steps were as long as max_step_s allowed: the cap, not the physics, set the pace.
  bool at_max_step;
};

class EnthalpySolver {
 public:
  /// `problem` must be consistent (sizes, fractions in [0, 1]); THAW_CHECK otherwise.
  explicit EnthalpySolver(GridProblem problem);
  ~EnthalpySolver();
  EnthalpySolver(const EnthalpySolver&) = delete;
  EnthalpySolver& operator=(const EnthalpySolver&) = delete;

  /// Advances to exactly t_target (> time()) or until no ice is left; returns the time reached.
  /// `stop` (if set, e.g. thaw::interrupt_requested) is asked between steps and Newton/CG
  /// iterations; once true, advance_to returns promptly, short of t_target, at the last
  /// accepted step (without flow, advancing again continues as if never stopped; with flow, the
  /// flow has already advanced over the discarded step, as on a rejected step). Throws GridRunaway
  /// when the run would not end (a collapsed step).
  double advance_to(double t_target, const std::function<bool()>& stop = {});
  double time() const;
  /// No ice left: nothing more to simulate.
  bool finished() const;
  GridSnapshot snapshot() const;
  GridField field() const;
  /// The body's faces whose heat GridSnapshot::face_heat_in_j holds, in its order.
  std::vector<std::string> face_names() const;
  const std::vector<GridEvent>& events() const;
  const GridStatistics& statistics() const;
  /// Scale of the relative energy error: latent heat of all initial material [J].
  double reference_energy() const;
  /// Per-cell liquid volume fraction (of the cell) and enthalpy [J/m^3 of material].
  std::vector<double> liquid_fraction() const;
  const std::vector<double>& material_fraction() const;
  const std::vector<double>& enthalpy() const;
  /// Cell volume [m^3] (full revolution for axisymmetric grids).
  double cell_volume(int i, int j, int k) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace thaw::sim
