#pragma once
// The pressure Poisson solve of the projection method, behind an interface a distributed back
// end (PETSc DMDA + KSP/PCMG) could fill: the operator is given by its face conductances on a
// box of cells, (L p)_c = sum over the faces f of c: g_f (p_c - p_neighbour), g_f >= 0 and zero
// on walls and closed faces, so L is symmetric positive semi-definite (constants per connected
// region span its null space). Knows nothing of velocities or fluids.
#include <array>
#include <vector>

namespace thaw::sim::flow {

struct PressureSolveReport {
  int iterations = 0;
  /// largest |b - L p| over the cells at the end
  double residual_max = 0;
  bool converged = false;
};

class PressureSolver {
 public:
  virtual ~PressureSolver() = default;
  /// cells {nx, ny, nz}; g[d]: conductances of the faces normal to axis d, laid out as
  /// MacGrid::face(d, ...) (n + e_d per axis).
  virtual void set_operator(const std::array<int, 3>& cells,
                            const std::array<std::vector<double>, 3>& g) = 0;
  /// The operator changed a little since set_operator (same cells): a back end may keep its
  /// preconditioner (the solve stays exact: only its speed depends on the preconditioner).
  virtual void update_operator(const std::array<int, 3>& cells,
                               const std::array<std::vector<double>, 3>& g) {
    set_operator(cells, g);
  }
  /// Solves L p = b until max |b - L p| <= tolerance, p holding the first guess. b must be
  /// consistent (sum zero over each connected region).
  virtual PressureSolveReport solve(const std::vector<double>& b, std::vector<double>& p,
                                    double tolerance) = 0;
};

}  // namespace thaw::sim::flow
