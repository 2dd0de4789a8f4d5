// The flow's pressure solve behind PressureSolver: the own multigrid-preconditioned CG
// (sim/flow/multigrid_pressure.h; 1 and 2 OpenMP threads) against PETSc's CG + BoomerAMG and
// CG + GAMG (sim/flow/petsc_pressure_solver.h; 1 rank, or every rank under mpirun -np N) on
// the same problems: the pressure Poisson problem of a closed N^3 box (conductances A/h, all
// walls closed, so the constants are the null space), a consistent right-hand side with smooth
// and cell-scale parts, solved from zero to max |b - L p| <= 1e-10 max |b| (the flow's own
// relative tolerance), each solve repeated REPEAT times. Prints per back end: the operator's
// set-up wall and CPU time, the solve's iterations, wall and CPU time per solve (CPU summed over
// the ranks), and cells solved per wall second (cells / wall time of one solve). Usage: [mpirun -np
// R] bench_pressure [N (48) [REPEAT (5)]]
#include <mpi.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <numbers>
#include <string>

#include "sim/flow/mac_grid.h"
#include "sim/flow/multigrid_pressure.h"
#include "sim/flow/petsc_pressure_solver.h"

namespace {

using namespace thaw::sim::flow;

struct Problem {
  MacGrid grid;
  std::array<std::vector<double>, 3> g;
  std::vector<double> b;
};

Problem make_problem(int n) {
  Problem p;
  p.grid.geometry = FlowGeometry::cartesian3d;
  p.grid.n = {n, n, n};
  p.grid.h_m = 1.0 / n;
  const MacGrid& g = p.grid;
  for (int d = 0; d < 3; ++d) {
    p.g[d].assign(g.face_count(d), 0.0);
    const auto f = g.face_dims(d);
    for (int k = 0; k < f[2]; ++k)
      for (int j = 0; j < f[1]; ++j)
        for (int i = 0; i < f[0]; ++i) {
          const int along = d == 0 ? i : (d == 1 ? j : k);
          if (along > 0 && along < n) p.g[d][g.face(d, i, j, k)] = g.face_area(d, i) / g.h_m;
        }
  }
  p.b.resize(g.cell_count());
  double sum = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = (i + 0.5) / n, y = (j + 0.5) / n, z = (k + 0.5) / n;
        const double v =
            std::sin(3 * std::numbers::pi * x) * std::cos(2 * std::numbers::pi * y) * (1 + z) +
            0.1 * std::sin(12.9898 * i + 78.233 * j + 37.719 * k);
        p.b[g.cell(i, j, k)] = v * g.h_m * g.h_m * g.h_m;
        sum += p.b[g.cell(i, j, k)];
      }
  for (double& v : p.b) v -= sum / static_cast<double>(p.b.size());  // consistent
  return p;
}

struct Timing {
  double setup_s = 0, setup_cpu_s = 0, wall_s = 0, cpu_s = 0;
  int iterations = 0;
  bool converged = true;
};

double cpu_now() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

Timing time_solver(PressureSolver& solver, const Problem& p, int repeat, MPI_Comm comm) {
  double bmax = 0;
  for (double v : p.b) bmax = std::max(bmax, std::abs(v));
  Timing t;
  MPI_Barrier(comm);
  double w0 = MPI_Wtime();
  const double s0 = cpu_now();
  solver.set_operator(p.grid.n, p.g);
  const double setup_cpu = cpu_now() - s0;
  MPI_Barrier(comm);
  t.setup_s = MPI_Wtime() - w0;
  MPI_Allreduce(&setup_cpu, &t.setup_cpu_s, 1, MPI_DOUBLE, MPI_SUM, comm);
  double cpu = 0;
  for (int r = 0; r < repeat; ++r) {
    std::vector<double> x(p.b.size(), 0.0);
    MPI_Barrier(comm);
    w0 = MPI_Wtime();
    const double c0 = cpu_now();
    const PressureSolveReport rep = solver.solve(p.b, x, 1e-10 * bmax);
    cpu += cpu_now() - c0;
    MPI_Barrier(comm);
    t.wall_s += MPI_Wtime() - w0;
    t.iterations = rep.iterations;
    t.converged = t.converged && rep.converged;
  }
  MPI_Allreduce(&cpu, &t.cpu_s, 1, MPI_DOUBLE, MPI_SUM, comm);
  t.wall_s /= repeat;
  t.cpu_s /= repeat;
  return t;
}

void print(const char* name, int workers, const Timing& t, std::size_t cells) {
  std::printf(
      "%-26s %d  set-up wall %7.3f s cpu %7.3f s  iterations %3d%s  solve wall %7.3f s  "
      "cpu %7.3f s  %.3g cells/s\n",
      name, workers, t.setup_s, t.setup_cpu_s, t.iterations, t.converged ? "" : " (NOT converged)",
      t.wall_s, t.cpu_s, static_cast<double>(cells) / t.wall_s);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const int n = argc > 1 ? std::atoi(argv[1]) : 48;
  const int repeat = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
  const Problem p = make_problem(n);
  const std::size_t cells = p.grid.cell_count();
  if (rank == 0)
    std::printf("pressure Poisson, closed %d^3 box (%zu cells), tolerance 1e-10 max|b|, %d ranks\n",
                n, cells, size);
  if (size == 1) {  // the own solver is shared-memory only
    for (int threads : {1, 2}) {
      omp_set_num_threads(threads);
      MultigridPressureSolver own;
      print("own MG-CG (threads)", threads, time_solver(own, p, repeat, MPI_COMM_SELF), cells);
    }
    omp_set_num_threads(1);
  }
  using Pc = PetscPressureSolver::Preconditioner;
  for (Pc pc : {Pc::boomeramg, Pc::gamg}) {
    PetscPressureSolver petsc(pc, PetscPressureSolver::Ranks::all);
    const Timing t = time_solver(petsc, p, repeat, MPI_COMM_WORLD);
    if (rank == 0)
      print(pc == Pc::boomeramg ? "PETSc CG+BoomerAMG (ranks)" : "PETSc CG+GAMG (ranks)", size, t,
            cells);
  }
  // PETSc was initialised by the solver after MPI_Init, so PETSc leaves MPI to us.
  PetscPressureSolver::finalize();
  MPI_Finalize();
  return 0;
}
