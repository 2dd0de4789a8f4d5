#pragma once
// The pressure solve on one machine: conjugate gradients preconditioned by one geometric
// multigrid V-cycle (cell-centred: children summed to restrict, the parent's value injected to
// prolong, coarse conductances the sum over the coarse face divided by 2, i.e. the operator
// rediscretised on the coarse cells (Braess 1984's scaled Galerkin coarse operator);
// symmetric red-black Gauss-Seidel smoothing, so the preconditioner is symmetric). Every loop
// writes disjoint cells and every sum is taken in a fixed order: the result does not depend on
// the thread count. With a diagonal (mass) term it also solves the Helmholtz problems of the
// flow's implicit viscous and conductive steps (coarse mass: the children's sum, P^T M P).
// Knows nothing of velocities or fluids.
#include <array>
#include <vector>

#include "sim/flow/pressure_solver.h"

namespace thaw::sim::flow {

class MultigridPressureSolver final : public PressureSolver {
 public:
  /// sweeps: red-black Gauss-Seidel sweeps before and after each coarse correction.
  explicit MultigridPressureSolver(int sweeps = 2, int max_iterations = 200);
  void set_operator(const std::array<int, 3>& cells,
                    const std::array<std::vector<double>, 3>& g) override;
  /// The operator plus a diagonal: (A x)_c = mass_c x_c + sum over c's faces g_f (x_c - x_nb),
  /// mass_c >= 0 (a cell with mass and no conductance is decoupled: x_c = b_c / mass_c).
  void set_operator(const std::array<int, 3>& cells, const std::array<std::vector<double>, 3>& g,
                    const std::vector<double>& mass);
  /// The finest level's operator replaced (same cells), the coarse levels kept as built: they
  /// only precondition, so CG still solves the new operator.
  void update_operator(const std::array<int, 3>& cells,
                       const std::array<std::vector<double>, 3>& g) override {
    update_operator(cells, g, {});
  }
  void update_operator(const std::array<int, 3>& cells, const std::array<std::vector<double>, 3>& g,
                       const std::vector<double>& mass);
  PressureSolveReport solve(const std::vector<double>& b, std::vector<double>& p,
                            double tolerance) override;
  /// Number of grid levels (1 = no coarsening).
  int levels() const { return static_cast<int>(levels_.size()); }

  struct Level {
    std::array<int, 3> n{1, 1, 1};
    std::array<std::vector<double>, 3> g;
    /// per cell: the conductances of its faces x-, x+, y-, y+, z-, z+
    std::array<std::vector<double>, 6> nb;
    std::vector<double> mass, diag, inv_diag, x, b, r;
    std::vector<double> zero;  ///< a row of zeros (neighbours beyond the box)
  };

 private:
  void v_cycle(int level);
  std::vector<Level> levels_;
  int sweeps_, max_iterations_;
};

}  // namespace thaw::sim::flow
