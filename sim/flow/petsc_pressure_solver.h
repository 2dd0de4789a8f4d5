#pragma once
// The pressure solve by PETSc (optional: built when THAW_PETSC is on, i.e. pkg-config finds
// PETSc, Debian's petsc-dev): the same operator as MultigridPressureSolver (pressure_solver.h,
// face conductances on a box of cells) assembled on a PETSc DMDA (a structured grid split in
// boxes over the MPI ranks of the communicator) and solved by KSP conjugate gradients
// preconditioned by algebraic multigrid: hypre's BoomerAMG (default) or PETSc's own GAMG. The
// constants of each connected region of cells span the operator's null space and are given to
// KSP as such; a cell with no open face keeps its value. Converged when max |b - L p| <=
// tolerance, the own solver's criterion. The options database can change anything under the
// prefix -thaw_pressure_ (e.g. -thaw_pressure_ksp_monitor).
// Every rank passes the whole arrays (as FlowSolver holds them) and gets the whole solution
// back: distributed, only the solve is shared out. Knows nothing of velocities or fluids.
#include <array>
#include <memory>
#include <vector>

#include "sim/flow/pressure_solver.h"

namespace thaw::sim::flow {

class PetscPressureSolver final : public PressureSolver {
 public:
  enum class Preconditioner { boomeramg, gamg };
  enum class Ranks { one, all };
  /// ranks: `one`: this process alone (PETSC_COMM_SELF); `all`: every rank of MPI_COMM_WORLD
  /// (all of them must make the same calls). Initialises PETSc (and MPI) if nobody has.
  explicit PetscPressureSolver(Preconditioner preconditioner = Preconditioner::boomeramg,
                               Ranks ranks = Ranks::one, int max_iterations = 200);
  ~PetscPressureSolver() override;
  void set_operator(const std::array<int, 3>& cells,
                    const std::array<std::vector<double>, 3>& g) override;
  PressureSolveReport solve(const std::vector<double>& b, std::vector<double>& p,
                            double tolerance) override;
  /// Number of MPI ranks the solve is shared by.
  int ranks() const;
  /// Finalises PETSc (and MPI, if PETSc started it) if a PetscPressureSolver initialised it;
  /// called at exit otherwise. Call it before MPI_Finalize when MPI is yours, after every
  /// solver is gone.
  static void finalize();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace thaw::sim::flow
