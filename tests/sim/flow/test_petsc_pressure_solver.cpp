// PETSc behind PressureSolver (sim/flow/petsc_pressure_solver.h) solves the same Poisson
// problems as the own multigrid-preconditioned CG (multigrid_pressure.h) to the same tolerance:
// planar, axisymmetric and 3D boxes, and a box cut in two closed regions with an isolated cell
// (a null space of two constants and a zero row), with BoomerAMG and with GAMG.
// The residual max |b - L x| is recomputed here from the conductances, and the two solutions
// agree within the bound the tolerance implies; also distributed over two MPI ranks.
#include "sim/flow/petsc_pressure_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/flow/mac_grid.h"
#include "sim/flow/multigrid_pressure.h"

namespace thaw::sim::flow {
namespace {

struct Poisson {
  MacGrid grid;
  std::array<std::vector<double>, 3> g;
  std::vector<int> region;  // per cell: its connected region, -1 for an isolated cell
};

/// Conductances A_f / h on an n x 1.5n (x n) box; cut: a closed plane at j = ny/2 and one
/// isolated cell.
Poisson make_poisson(FlowGeometry geometry, int n, bool cut) {
  Poisson p;
  p.grid.geometry = geometry;
  p.grid.n = {n, n + n / 2, geometry == FlowGeometry::cartesian3d ? n : 1};
  p.grid.h_m = 1.0 / n;
  const MacGrid& g = p.grid;
  for (int d = 0; d < 3; ++d) {
    p.g[d].assign(g.face_count(d), 0.0);
    if (d >= g.dims()) continue;
    const auto f = g.face_dims(d);
    for (int k = 0; k < f[2]; ++k)
      for (int j = 0; j < f[1]; ++j)
        for (int i = 0; i < f[0]; ++i) {
          const int along = d == 0 ? i : (d == 1 ? j : k);
          const bool closed = cut && d == 1 && j == g.n[1] / 2;
          if (along > 0 && along < g.n[d] && !closed)
            p.g[d][g.face(d, i, j, k)] = g.face_area(d, i) / g.h_m;
        }
  }
  p.region.assign(g.cell_count(), 0);
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) p.region[g.cell(i, j, k)] = cut && j >= g.n[1] / 2;
  if (cut) {  // isolate cell (1, 1, 0): close its faces
    const int i = 1, j = 1;
    for (int d = 0; d < g.dims(); ++d) {
      int lo[3] = {i, j, 0}, hi[3] = {i, j, 0};
      ++hi[d];
      p.g[d][g.face(d, lo[0], lo[1], lo[2])] = 0;
      p.g[d][g.face(d, hi[0], hi[1], hi[2])] = 0;
    }
    p.region[g.cell(i, j, 0)] = -1;
  }
  return p;
}

/// (L x)_c = sum over c's open faces g_f (x_c - x_nb)
std::vector<double> laplacian(const Poisson& P, const std::vector<double>& x) {
  const MacGrid& g = P.grid;
  std::vector<double> out(g.cell_count(), 0.0);
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const std::size_t c = g.cell(i, j, k);
        for (int d = 0; d < g.dims(); ++d) {
          int hi[3] = {i, j, k}, nb[3] = {i, j, k};
          ++hi[d];
          ++nb[d];
          const double gf = P.g[d][g.face(d, hi[0], hi[1], hi[2])];
          if (!(gf > 0)) continue;
          const std::size_t o = g.cell(nb[0], nb[1], nb[2]);
          out[c] += gf * (x[c] - x[o]);
          out[o] += gf * (x[o] - x[c]);
        }
      }
  return out;
}

double max_abs_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0;
  for (std::size_t c = 0; c < a.size(); ++c) m = std::max(m, std::abs(a[c] - b[c]));
  return m;
}

/// max |a - b| over the cells of the regions (an isolated cell's row is zero: any value solves)
double max_abs_difference_open(const Poisson& P, const std::vector<double>& a,
                               const std::vector<double>& b) {
  double m = 0;
  for (std::size_t c = 0; c < a.size(); ++c)
    if (P.region[c] >= 0) m = std::max(m, std::abs(a[c] - b[c]));
  return m;
}

/// Each region's mean removed (the null space); isolated cells as they are.
std::vector<double> without_constants(const Poisson& P, std::vector<double> x) {
  double sum[2] = {0, 0}, count[2] = {0, 0};
  for (std::size_t c = 0; c < x.size(); ++c)
    if (P.region[c] >= 0) {
      sum[P.region[c]] += x[c];
      ++count[P.region[c]];
    }
  for (std::size_t c = 0; c < x.size(); ++c)
    if (P.region[c] >= 0) x[c] -= sum[P.region[c]] / count[P.region[c]];
  return x;
}

void solve_both(FlowGeometry geometry, int n, bool cut,
                PetscPressureSolver::Preconditioner preconditioner,
                PetscPressureSolver::Ranks ranks = PetscPressureSolver::Ranks::one) {
  const Poisson P = make_poisson(geometry, n, cut);
  const MacGrid& g = P.grid;
  std::vector<double> exact(g.cell_count());
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
        exact[g.cell(i, j, k)] = std::cos(std::numbers::pi * (i + 0.5) / g.n[0]) *
                                 std::cos(2 * std::numbers::pi * (j + 0.5) / g.n[1]) *
                                 (1.0 + 0.3 * std::sin(0.7 * k));
  const std::vector<double> b = laplacian(P, exact);  // consistent: sums to zero per region
  double bmax = 0;
  for (double v : b) bmax = std::max(bmax, std::abs(v));
  const double tolerance = 1e-10 * bmax;

  std::vector<double> x_own(g.cell_count(), 0.0), x_petsc(g.cell_count(), 0.0);
  MultigridPressureSolver own;
  own.set_operator(g.n, P.g);
  const PressureSolveReport r_own = own.solve(b, x_own, tolerance);
  PetscPressureSolver petsc(preconditioner, ranks);
  petsc.set_operator(g.n, P.g);
  const PressureSolveReport r_petsc = petsc.solve(b, x_petsc, tolerance);

  const double res_own = max_abs_difference(laplacian(P, x_own), b);
  const double res_petsc = max_abs_difference(laplacian(P, x_petsc), b);
  std::printf(
      "geometry %d, %zu cells%s, %s: iterations own %d petsc %d, residual own %.2e petsc %.2e "
      "(tolerance %.2e)\n",
      static_cast<int>(geometry), g.cell_count(), cut ? ", cut" : "",
      preconditioner == PetscPressureSolver::Preconditioner::boomeramg ? "BoomerAMG" : "GAMG",
      r_own.iterations, r_petsc.iterations, res_own, res_petsc, tolerance);
  EXPECT_TRUE(r_own.converged);
  EXPECT_TRUE(r_petsc.converged);
  // Both reach the tolerance in the true residual (the own solver's recurrence may drift from
  // it by rounding: 1e-3 of the tolerance is far above the ~1e-16 bmax sqrt(iterations) drift).
  EXPECT_LE(res_own, tolerance * (1 + 1e-3));
  EXPECT_LE(res_petsc, tolerance * (1 + 1e-3));
  EXPECT_NEAR(r_petsc.residual_max, res_petsc, 1e-3 * tolerance);
  // PETSc's isolated cell keeps its first guess (0): its row is x_c = p_c, solved to the
  // tolerance.
  if (cut) {
    EXPECT_NEAR(x_petsc[g.cell(1, 1, 0)], 0.0, tolerance);
  }
  // Agreement: each error e = x - exact (less the null space) has ||e||_2 <= ||r||_2 / lambda,
  // lambda the smallest non-zero eigenvalue of L on a region, at least g_min * 4 sin^2(pi / 2m)
  // (L >= g_min times the grid graph's Laplacian, whose smallest is that, m the longest side);
  // ||r||_2 <= sqrt(N) tolerance.
  double g_min = INFINITY;
  for (int d = 0; d < g.dims(); ++d)
    for (double v : P.g[d])
      if (v > 0) g_min = std::min(g_min, v);
  const int m = std::max({g.n[0], g.n[1], g.n[2]});
  const double lambda = g_min * 4 * std::pow(std::sin(std::numbers::pi / (2 * m)), 2);
  const double bound = 2 * std::sqrt(static_cast<double>(g.cell_count())) * tolerance / lambda;
  EXPECT_LE(max_abs_difference_open(P, without_constants(P, x_own), without_constants(P, x_petsc)),
            bound);
  // and both are the discrete solution (to that bound) of the problem built from `exact`
  EXPECT_LE(max_abs_difference_open(P, without_constants(P, x_petsc), without_constants(P, exact)),
            bound);
}

TEST(PetscPressureSolver, SolvesTheOwnSolversProblemsToTheSameTolerance) {
  using Pc = PetscPressureSolver::Preconditioner;
  for (Pc pc : {Pc::boomeramg, Pc::gamg}) {
    solve_both(FlowGeometry::planar, 48, false, pc);
    solve_both(FlowGeometry::axisymmetric, 48, false, pc);
    solve_both(FlowGeometry::cartesian3d, 16, false, pc);
    solve_both(FlowGeometry::planar, 32, true, pc);
    solve_both(FlowGeometry::cartesian3d, 12, true, pc);
  }
}

// Over every rank of MPI_COMM_WORLD: one rank under ctest's plain run, two under the
// PetscPressureSolverTwoRanks test (mpirun -np 2), where the DMDA splits the boxes.
TEST(PetscPressureSolverDistributed, SolvesTheSameProblemsOverTheRanks) {
  using Pc = PetscPressureSolver::Preconditioner;
  const auto all = PetscPressureSolver::Ranks::all;
  solve_both(FlowGeometry::axisymmetric, 48, false, Pc::boomeramg, all);
  solve_both(FlowGeometry::cartesian3d, 16, false, Pc::boomeramg, all);
  solve_both(FlowGeometry::cartesian3d, 12, true, Pc::boomeramg, all);
  solve_both(FlowGeometry::cartesian3d, 12, true, Pc::gamg, all);
}

TEST(PetscPressureSolver, AWarmStartThatSolvesTakesNoIteration) {
  const Poisson P = make_poisson(FlowGeometry::cartesian3d, 8, false);
  std::vector<double> x(P.grid.cell_count());
  for (std::size_t c = 0; c < x.size(); ++c) x[c] = std::sin(0.1 * static_cast<double>(c));
  const std::vector<double> b = laplacian(P, x);
  PetscPressureSolver petsc;
  petsc.set_operator(P.grid.n, P.g);
  const PressureSolveReport r = petsc.solve(b, x, 1e-9);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.iterations, 0);
}

}  // namespace
}  // namespace thaw::sim::flow
