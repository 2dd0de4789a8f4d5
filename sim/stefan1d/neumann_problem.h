#pragma once
// The planar Neumann problems as runs of the front-fixing solver, shared by the validation tests
// and the convergence-table program (bench/sim/sim_convergence): the scenario and exact start for
// melting from a heated face into subcooled ice, or freezing from a cold face into warm water,
// and the comparison of a run with the exact solution.
#include <cmath>

#include "sim/reference/neumann.h"
#include "sim/stefan1d/front_fixing.h"

namespace thaw::sim {

struct NeumannProblem {
  bool melting = true;  ///< melting from a heated inner face, else freezing from the outer face
  double face_excess_k = 0;  ///< |T_face - T_m| [K]
  double far_excess_k = 0;   ///< |T_far - T_m| [K] (subcooling of the ice / superheat of the water)
  double t0_s = 100, t1_s = 1000;  ///< start from the exact profile at t0, compare at t1
  int cells_per_phase = 40;
  double time_tolerance = 1e-11;
  double fixed_step_s = 0;  ///< > 0: constant steps (order in time)
  Materials materials;
};

struct NeumannComparison {
  double front_m = 0, exact_front_m = 0;  ///< distance of the front from the face at t1 [m]
  double temperature_error_k = 0;         ///< max |T - T_exact| over the profile points at t1
  double energy_balance_error = 0;        ///< cumulative, relative
  double heat_in_j = 0;  ///< heat entered through both ends over [t0, t1] per m^2 (the solver's)
  long steps = 0;
  double relative_front_error() const { return std::abs(front_m - exact_front_m) / exact_front_m; }
};

/// The exact solution of a problem.
NeumannSolution neumann_solution(const NeumannProblem& problem);
/// Runs the solver on the problem: planar domain reaching 10 sqrt(alpha_far t1) beyond the exact
/// front at t1 (held at T_far, or a symmetry plane for freezing), started at t0 from the exact
/// profile, compared at t1.
NeumannComparison run_neumann_problem(const NeumannProblem& problem);

}  // namespace thaw::sim
