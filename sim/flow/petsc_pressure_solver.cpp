// PetscPressureSolver: DMDA + KSP CG + BoomerAMG/GAMG behind PressureSolver (see the header).
#include "sim/flow/petsc_pressure_solver.h"

#include <petscdmda.h>
#include <petscksp.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>

#include "base/check.h"

namespace thaw::sim::flow {
namespace {

void check(PetscErrorCode e, const char* what) {
  THAW_CHECK(e == 0, what);
}

std::size_t cell_of(const std::array<int, 3>& n, int i, int j, int k) {
  return static_cast<std::size_t>(i) +
         static_cast<std::size_t>(n[0]) *
             (static_cast<std::size_t>(j) + static_cast<std::size_t>(n[1]) * k);
}

std::size_t face_of(const std::array<int, 3>& n, int d, int i, int j, int k) {
  std::array<int, 3> f = n;
  ++f[d];
  return static_cast<std::size_t>(i) +
         static_cast<std::size_t>(f[0]) *
             (static_cast<std::size_t>(j) + static_cast<std::size_t>(f[1]) * k);
}

/// PETSc's options under the solver's prefix, unless the user set them.
void default_option(const char* name, const char* value) {
  PetscBool set = PETSC_FALSE;
  check(PetscOptionsHasName(nullptr, nullptr, name, &set), "PetscOptionsHasName");
  if (!set) check(PetscOptionsSetValue(nullptr, name, value), "PetscOptionsSetValue");
}

bool g_initialised_here = false;

}  // namespace

struct PetscPressureSolver::Impl {
  Preconditioner preconditioner;
  MPI_Comm comm = PETSC_COMM_SELF;
  int max_iterations = 200;
  std::array<int, 3> n{0, 0, 0};
  // per cell: the conductances of its six faces x-, x+, y-, y+, z-, z+ (whole grid, every rank)
  std::array<std::vector<double>, 6> nb;
  std::vector<char> isolated;  // no open face: the cell keeps its value
  DM da = nullptr;
  Mat A = nullptr;
  KSP ksp = nullptr;
  MatNullSpace null_space = nullptr;
  Vec x = nullptr, rhs = nullptr, natural = nullptr, everything = nullptr, work = nullptr;
  VecScatter to_all = nullptr;
  double tolerance = 0;

  void destroy() {
    if (to_all) VecScatterDestroy(&to_all);
    for (Vec* v : {&x, &rhs, &natural, &everything, &work})
      if (*v) VecDestroy(v);
    if (null_space) MatNullSpaceDestroy(&null_space);
    if (ksp) KSPDestroy(&ksp);
    if (A) MatDestroy(&A);
    if (da) DMDestroy(&da);
  }

  /// Converged when max |b - A x| <= tolerance. KSP hands the residual's 2-norm r2 (the
  /// unpreconditioned norm); max|r| <= r2 <= sqrt(N) max|r|, so the true residual is formed only
  /// when r2 cannot decide.
  static PetscErrorCode converged(KSP ksp, PetscInt it, PetscReal r2, KSPConvergedReason* reason,
                                  void* context) {
    auto* self = static_cast<Impl*>(context);
    *reason = KSP_CONVERGED_ITERATING;
    PetscInt size = 0;
    PetscCall(VecGetSize(self->x, &size));
    if (r2 <= self->tolerance) {
      *reason = KSP_CONVERGED_ATOL;
    } else if (r2 <= self->tolerance * std::sqrt(static_cast<double>(size))) {
      Vec r = nullptr;
      PetscCall(KSPBuildResidual(ksp, nullptr, self->work, &r));
      PetscReal rmax = 0;
      PetscCall(VecNorm(r, NORM_INFINITY, &rmax));
      if (rmax <= self->tolerance) *reason = KSP_CONVERGED_ATOL;
    }
    if (*reason == KSP_CONVERGED_ITERATING && it >= self->max_iterations)
      *reason = KSP_DIVERGED_ITS;
    return 0;
  }
};

PetscPressureSolver::PetscPressureSolver(Preconditioner preconditioner, Ranks ranks,
                                         int max_iterations)
    : impl_(std::make_unique<Impl>()) {
  PetscBool up = PETSC_FALSE;
  check(PetscInitialized(&up), "PetscInitialized");
  if (!up) {
    check(PetscInitializeNoArguments(), "PetscInitializeNoArguments");
    g_initialised_here = true;
    std::atexit(&PetscPressureSolver::finalize);
  }
  impl_->preconditioner = preconditioner;
  impl_->comm = ranks == Ranks::all ? PETSC_COMM_WORLD : PETSC_COMM_SELF;
  impl_->max_iterations = max_iterations;
}

PetscPressureSolver::~PetscPressureSolver() {
  impl_->destroy();
}

void PetscPressureSolver::finalize() {
  if (!g_initialised_here) return;
  g_initialised_here = false;
  int mpi_finalized = 0;
  MPI_Finalized(&mpi_finalized);
  if (!mpi_finalized) PetscFinalize();
}

int PetscPressureSolver::ranks() const {
  int size = 1;
  MPI_Comm_size(impl_->comm, &size);
  return size;
}

void PetscPressureSolver::set_operator(const std::array<int, 3>& cells,
                                       const std::array<std::vector<double>, 3>& g) {
  Impl& m = *impl_;
  m.destroy();
  m.n = cells;
  const auto& n = cells;
  const std::size_t count = static_cast<std::size_t>(n[0]) * n[1] * n[2];
  for (auto& v : m.nb) v.assign(count, 0.0);
  for (int d = 0; d < 3; ++d) {
    std::array<int, 3> f = n;
    ++f[d];
    THAW_CHECK(g[d].size() == static_cast<std::size_t>(f[0]) * f[1] * f[2],
               "petsc pressure: conductances of the wrong size");
  }
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const std::size_t c = cell_of(n, i, j, k);
        const int idx[3] = {i, j, k};
        for (int d = 0; d < 3; ++d) {
          int hi[3] = {i, j, k};
          ++hi[d];
          m.nb[2 * d][c] = idx[d] > 0 ? g[d][face_of(n, d, i, j, k)] : 0.0;
          m.nb[2 * d + 1][c] = idx[d] < n[d] - 1 ? g[d][face_of(n, d, hi[0], hi[1], hi[2])] : 0.0;
        }
      }
  m.isolated.assign(count, 1);
  for (std::size_t c = 0; c < count; ++c)
    for (int f = 0; f < 6; ++f)
      if (m.nb[f][c] > 0) m.isolated[c] = 0;

  check(DMDACreate3d(m.comm, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DM_BOUNDARY_NONE,
                     DMDA_STENCIL_STAR, n[0], n[1], n[2], PETSC_DECIDE, PETSC_DECIDE, PETSC_DECIDE,
                     1, 1, nullptr, nullptr, nullptr, &m.da),
        "DMDACreate3d");
  check(DMSetUp(m.da), "DMSetUp");
  check(DMCreateMatrix(m.da, &m.A), "DMCreateMatrix");
  PetscInt xs, ys, zs, xm, ym, zm;
  check(DMDAGetCorners(m.da, &xs, &ys, &zs, &xm, &ym, &zm), "DMDAGetCorners");
  for (PetscInt k = zs; k < zs + zm; ++k)
    for (PetscInt j = ys; j < ys + ym; ++j)
      for (PetscInt i = xs; i < xs + xm; ++i) {
        const std::size_t c = cell_of(n, i, j, k);
        MatStencil row{};
        row.i = i;
        row.j = j;
        row.k = k;
        MatStencil cols[7];
        PetscScalar vals[7];
        int used = 0;
        double diag = 0;
        const PetscInt step[6][3] = {{-1, 0, 0}, {1, 0, 0},  {0, -1, 0},
                                     {0, 1, 0},  {0, 0, -1}, {0, 0, 1}};
        for (int f = 0; f < 6; ++f) {
          const double gf = m.nb[f][c];
          if (!(gf > 0)) continue;
          cols[used] = row;
          cols[used].i += step[f][0];
          cols[used].j += step[f][1];
          cols[used].k += step[f][2];
          vals[used++] = -gf;
          diag += gf;
        }
        cols[used] = row;
        vals[used++] = m.isolated[c] ? 1.0 : diag;
        check(MatSetValuesStencil(m.A, 1, &row, used, cols, vals, INSERT_VALUES),
              "MatSetValuesStencil");
      }
  check(MatAssemblyBegin(m.A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(m.A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  check(MatSetOption(m.A, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");

  // The null space: per connected region of open cells, its indicator (normalised). Regions by
  // a flood fill over the open faces, in cell order (the same on every rank).
  std::vector<int> region(count, -1);
  std::vector<std::size_t> stack;
  int regions = 0;
  std::vector<std::size_t> region_size;
  const std::ptrdiff_t offset[6] = {-1,
                                    1,
                                    -static_cast<std::ptrdiff_t>(n[0]),
                                    static_cast<std::ptrdiff_t>(n[0]),
                                    -static_cast<std::ptrdiff_t>(n[0]) * n[1],
                                    static_cast<std::ptrdiff_t>(n[0]) * n[1]};
  for (std::size_t seed = 0; seed < count; ++seed) {
    if (m.isolated[seed] || region[seed] >= 0) continue;
    region[seed] = regions;
    region_size.push_back(0);
    stack.assign(1, seed);
    while (!stack.empty()) {
      const std::size_t c = stack.back();
      stack.pop_back();
      ++region_size[regions];
      for (int f = 0; f < 6; ++f) {
        if (!(m.nb[f][c] > 0)) continue;
        const std::size_t o = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(c) + offset[f]);
        if (region[o] < 0) {
          region[o] = regions;
          stack.push_back(o);
        }
      }
    }
    ++regions;
  }
  std::vector<Vec> basis(regions);
  for (int r = 0; r < regions; ++r) {
    check(DMCreateGlobalVector(m.da, &basis[r]), "DMCreateGlobalVector");
    PetscScalar*** a;
    check(DMDAVecGetArray(m.da, basis[r], &a), "DMDAVecGetArray");
    const double value = 1.0 / std::sqrt(static_cast<double>(region_size[r]));
    for (PetscInt k = zs; k < zs + zm; ++k)
      for (PetscInt j = ys; j < ys + ym; ++j)
        for (PetscInt i = xs; i < xs + xm; ++i)
          a[k][j][i] = region[cell_of(n, i, j, k)] == r ? value : 0.0;
    check(DMDAVecRestoreArray(m.da, basis[r], &a), "DMDAVecRestoreArray");
  }
  check(MatNullSpaceCreate(m.comm, PETSC_FALSE, regions, basis.data(), &m.null_space),
        "MatNullSpaceCreate");
  for (Vec& v : basis) VecDestroy(&v);
  check(MatSetNullSpace(m.A, m.null_space), "MatSetNullSpace");
  check(MatSetTransposeNullSpace(m.A, m.null_space), "MatSetTransposeNullSpace");

  check(DMCreateGlobalVector(m.da, &m.x), "DMCreateGlobalVector");
  check(VecDuplicate(m.x, &m.rhs), "VecDuplicate");
  check(VecDuplicate(m.x, &m.work), "VecDuplicate");
  check(DMDACreateNaturalVector(m.da, &m.natural), "DMDACreateNaturalVector");
  check(VecScatterCreateToAll(m.natural, &m.to_all, &m.everything), "VecScatterCreateToAll");

  check(KSPCreate(m.comm, &m.ksp), "KSPCreate");
  check(KSPSetOptionsPrefix(m.ksp, "thaw_pressure_"), "KSPSetOptionsPrefix");
  check(KSPSetOperators(m.ksp, m.A, m.A), "KSPSetOperators");
  check(KSPSetType(m.ksp, KSPCG), "KSPSetType");
  PC pc;
  check(KSPGetPC(m.ksp, &pc), "KSPGetPC");
  if (m.preconditioner == Preconditioner::boomeramg) {
    check(PCSetType(pc, PCHYPRE), "PCSetType");
    check(PCHYPRESetType(pc, "boomeramg"), "PCHYPRESetType");
    // hypre's advice for 3D Laplacians (the default 0.25 suits 2D)
    if (n[2] > 1) default_option("-thaw_pressure_pc_hypre_boomeramg_strong_threshold", "0.5");
  } else {
    check(PCSetType(pc, PCGAMG), "PCSetType");
  }
  check(KSPSetNormType(m.ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
  check(KSPSetInitialGuessNonzero(m.ksp, PETSC_TRUE), "KSPSetInitialGuessNonzero");
  check(KSPSetConvergenceTest(m.ksp, &Impl::converged, &m, nullptr), "KSPSetConvergenceTest");
  check(KSPSetTolerances(m.ksp, 0.0, 0.0, PETSC_DEFAULT, m.max_iterations), "KSPSetTolerances");
  check(KSPSetFromOptions(m.ksp), "KSPSetFromOptions");
  check(KSPSetUp(m.ksp), "KSPSetUp");
}

PressureSolveReport PetscPressureSolver::solve(const std::vector<double>& b, std::vector<double>& p,
                                               double tolerance) {
  Impl& m = *impl_;
  THAW_CHECK(m.ksp != nullptr, "pressure solve before set_operator");
  const auto& n = m.n;
  const std::size_t count = static_cast<std::size_t>(n[0]) * n[1] * n[2];
  THAW_CHECK(b.size() == count && p.size() == count, "pressure solve: vector of the wrong size");
  m.tolerance = tolerance;
  PetscInt xs, ys, zs, xm, ym, zm;
  check(DMDAGetCorners(m.da, &xs, &ys, &zs, &xm, &ym, &zm), "DMDAGetCorners");
  PetscScalar ***xa, ***ba;
  check(DMDAVecGetArray(m.da, m.x, &xa), "DMDAVecGetArray");
  check(DMDAVecGetArray(m.da, m.rhs, &ba), "DMDAVecGetArray");
  for (PetscInt k = zs; k < zs + zm; ++k)
    for (PetscInt j = ys; j < ys + ym; ++j)
      for (PetscInt i = xs; i < xs + xm; ++i) {
        const std::size_t c = cell_of(n, i, j, k);
        xa[k][j][i] = p[c];
        ba[k][j][i] = m.isolated[c] ? p[c] : b[c];  // an isolated row is x_c = p_c
      }
  check(DMDAVecRestoreArray(m.da, m.x, &xa), "DMDAVecRestoreArray");
  check(DMDAVecRestoreArray(m.da, m.rhs, &ba), "DMDAVecRestoreArray");
  check(KSPSolve(m.ksp, m.rhs, m.x), "KSPSolve");

  PressureSolveReport report;
  PetscInt iterations = 0;
  check(KSPGetIterationNumber(m.ksp, &iterations), "KSPGetIterationNumber");
  KSPConvergedReason reason;
  check(KSPGetConvergedReason(m.ksp, &reason), "KSPGetConvergedReason");
  report.iterations = static_cast<int>(iterations);
  report.converged = reason > 0;
  // the true residual, as the own solver reports it
  check(MatMult(m.A, m.x, m.work), "MatMult");
  check(VecAYPX(m.work, -1.0, m.rhs), "VecAYPX");
  PetscReal rmax = 0;
  check(VecNorm(m.work, NORM_INFINITY, &rmax), "VecNorm");
  report.residual_max = rmax;

  // the whole solution to every rank, in the natural (MacGrid::cell) order
  check(DMDAGlobalToNaturalBegin(m.da, m.x, INSERT_VALUES, m.natural), "DMDAGlobalToNatural");
  check(DMDAGlobalToNaturalEnd(m.da, m.x, INSERT_VALUES, m.natural), "DMDAGlobalToNatural");
  check(VecScatterBegin(m.to_all, m.natural, m.everything, INSERT_VALUES, SCATTER_FORWARD),
        "VecScatterBegin");
  check(VecScatterEnd(m.to_all, m.natural, m.everything, INSERT_VALUES, SCATTER_FORWARD),
        "VecScatterEnd");
  const PetscScalar* all;
  check(VecGetArrayRead(m.everything, &all), "VecGetArrayRead");
  std::copy(all, all + count, p.begin());
  check(VecRestoreArrayRead(m.everything, &all), "VecRestoreArrayRead");
  return report;
}

}  // namespace thaw::sim::flow
