// thaw's flow solver (sim/flow/flow_solver.h, driven directly as the cavity tests do) on the
// differentially heated cube at Ra 1e5, Pr 0.71: the peer of the OpenFOAM case in
// bench/sim/openfoam_cube/ (issue 24, Performance). Free-fall units: side L = 1, g beta dT = 1,
// walls x_min at +1/2 (hot) and x_max at -1/2 (cold), the four others adiabatic, all no-slip;
// nu = sqrt(Pr / Ra), alpha = 1 / sqrt(Ra Pr). The hot wall's mean Nusselt number is
// Q_hot / (alpha dT L) (the solver's wall heat flow is alpha * integral dT/dn dA).
// Marches from rest at T = 0 until steady: the largest |dT/dt| below RATE and the two walls'
// Nusselt numbers equal to BALANCE (relative). Prints per grid: cells, threads, steps, wall and
// process CPU seconds, Nu hot and cold, the error against Tric, Labrosse & Betrouni (2000), and
// the wall time at which Nu hot last entered 1e-3 and 1e-4 (relative) of its final value
// (the "settled" times the OpenFOAM run is measured by as well). With two or more grids, the
// Richardson extrapolation of the last two (formal order 2; the grids must halve the cell).
// SEQUENCE=1 in the environment: grid sequencing (nested iteration) -- each grid after the first
// starts from the previous grid's steady state, prolonged (temperature trilinear; velocity
// exactly divergence-free: a fine face on a coarse face takes its value, a fine face inside a
// coarse cell the mean of the cell's two faces), and the times printed add up the grids so far.
// PRESSURE=boomeramg|gamg in the environment (builds with THAW_PETSC): the flow's pressure
// solves by PetscPressureSolver instead of the own multigrid (the viscous and conductive
// Helmholtz solves stay the own).
// COURANT=c in the environment: the step's Courant number (FlowProblem::courant, default 0.5).
// Usage: bench_flow_cube [THREADS [RATE [BALANCE [N1 N2 ...]]]]  (default 1 1e-5 1e-4 16 32)
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "base/check.h"
#include "sim/flow/flow_solver.h"
#ifdef THAW_HAVE_PETSC
#include "sim/flow/petsc_pressure_solver.h"
#endif

namespace {

using namespace thaw::sim::flow;

/// Tric, Labrosse & Betrouni (2000), Int. J. Heat Mass Transfer 43:4043, pseudo-spectral
/// Chebyshev solution of the air-filled cube: mean Nusselt number of the hot wall at Ra 1e5
/// (quoted from memory of the paper's table, not checked against a copy: docs/benchmarks.md).
constexpr double kTricNu1e5 = 4.3370;
constexpr double kRayleigh = 1e5, kPrandtl = 0.71;

FlowProblem cube_problem(int cells) {
  FlowProblem p;
  p.grid.geometry = FlowGeometry::cartesian3d;
  p.grid.n = {cells, cells, cells};
  p.grid.h_m = 1.0 / cells;
  p.fluid.density = FluidModel::Density::linear;
  p.fluid.reference_density_kg_m3 = 1.0;
  p.fluid.expansion_per_k = 1.0;
  p.fluid.reference_temperature_c = 0.0;
  p.fluid.gravity_m_s2 = 1.0;
  p.fluid.viscosity_pa_s = std::sqrt(kPrandtl / kRayleigh);  // rho_0 = 1: nu
  p.thermal_diffusivity_m2_s = 1.0 / std::sqrt(kRayleigh * kPrandtl);
  p.walls[x_min] = {WallCondition::Kind::temperature, 0.5};
  p.walls[x_max] = {WallCondition::Kind::temperature, -0.5};
  if (const char* courant = std::getenv("COURANT")) p.courant = std::atof(courant);
  return p;
}

struct Sample {
  double time, wall_s, cpu_s, nusselt_hot;
};

/// The first sample after which every later sample's Nu stays within tol (relative) of the
/// last one.
const Sample& settled(const std::vector<Sample>& history, double tol) {
  const double last = history.back().nusselt_hot;
  std::size_t at = 0;
  for (std::size_t i = 0; i < history.size(); ++i)
    if (std::abs(history[i].nusselt_hot - last) > tol * std::abs(last)) at = i + 1;
  return history[std::min(at, history.size() - 1)];
}

/// The steady state of a grid: its fields, for the next grid of a sequence.
struct State {
  int cells = 0;
  std::vector<double> temperature;
  std::array<std::vector<double>, 3> velocity;
  double wall_s = 0, cpu_s = 0;  // spent to get it, the grids before included
};

/// Prolongs a steady state on n^3 cells to (2n)^3 (see the header comment) and sets it.
void prolong(const State& coarse, FlowSolver& fine) {
  const int n = coarse.cells, m = 2 * n;
  THAW_CHECK(fine.grid().n[0] == m, "grid sequencing: each grid halves the cell");
  MacGrid cg = fine.grid();
  cg.n = {n, n, n};
  cg.h_m = 2 * fine.grid().h_m;
  auto& t = fine.temperature_c();
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        // the fine centre in coarse cell-centre coordinates, clamped to the coarse centres
        int lo[3];
        double w[3];
        const int idx[3] = {i, j, k};
        for (int d = 0; d < 3; ++d) {
          const double x = std::clamp((idx[d] + 0.5) / 2.0 - 0.5, 0.0, n - 1.0);
          lo[d] = std::min(static_cast<int>(x), n - 2);
          w[d] = x - lo[d];
        }
        double v = 0;
        for (int c = 0; c < 8; ++c) {
          const int a = c & 1, b = (c >> 1) & 1, e = (c >> 2) & 1;
          v += (a ? w[0] : 1 - w[0]) * (b ? w[1] : 1 - w[1]) * (e ? w[2] : 1 - w[2]) *
               coarse.temperature[cg.cell(lo[0] + a, lo[1] + b, lo[2] + e)];
        }
        t[fine.grid().cell(i, j, k)] = v;
      }
  for (int d = 0; d < 3; ++d) {
    std::vector<double> u(fine.grid().face_count(d));
    const auto f = fine.grid().face_dims(d);
    for (int k = 0; k < f[2]; ++k)
      for (int j = 0; j < f[1]; ++j)
        for (int i = 0; i < f[0]; ++i) {
          int c[3] = {i / 2, j / 2, k / 2};
          const int along = d == 0 ? i : (d == 1 ? j : k);
          double v;
          if (along % 2 == 0) {  // on a coarse face
            c[d] = along / 2;
            v = coarse.velocity[d][cg.face(d, c[0], c[1], c[2])];
          } else {  // inside coarse cell along / 2: the mean of its two faces along d
            c[d] = along / 2;
            int c1[3] = {c[0], c[1], c[2]};
            ++c1[d];
            v = 0.5 * (coarse.velocity[d][cg.face(d, c[0], c[1], c[2])] +
                       coarse.velocity[d][cg.face(d, c1[0], c1[1], c1[2])]);
          }
          u[fine.grid().face(d, i, j, k)] = v;
        }
    fine.set_velocity_m_s(d, std::move(u));
  }
}

double run(int cells, int threads, double rate_tolerance, double balance_tolerance,
           State* sequence) {
  omp_set_num_threads(threads);
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  std::unique_ptr<PressureSolver> pressure;
  if (const char* back_end = std::getenv("PRESSURE"); back_end && *back_end) {
#ifdef THAW_HAVE_PETSC
    const std::string b = back_end;
    THAW_CHECK(b == "boomeramg" || b == "gamg", "PRESSURE is boomeramg or gamg");
    pressure = std::make_unique<PetscPressureSolver>(
        b == "gamg" ? PetscPressureSolver::Preconditioner::gamg
                    : PetscPressureSolver::Preconditioner::boomeramg);
#else
    THAW_CHECK(back_end == nullptr, "PRESSURE needs a build with THAW_PETSC");
#endif
  }
  FlowSolver s(cube_problem(cells), std::move(pressure));
  const double wall_before = sequence ? sequence->wall_s : 0,
               cpu_before = sequence ? sequence->cpu_s : 0;
  if (sequence && sequence->cells > 0) prolong(*sequence, s);
  const double alpha = s.problem().thermal_diffusivity_m2_s;
  std::vector<double> before;
  std::vector<Sample> history;
  long steps = 0;
  double nu_hot = 0, nu_cold = 0, rate = 0;
  for (;;) {
    const double dt = s.stable_time_step_s();
    before = s.temperature_c();
    s.step(dt);
    ++steps;
    rate = 0;
    for (std::size_t c = 0; c < before.size(); ++c)
      rate = std::max(rate, std::abs(s.temperature_c()[c] - before[c]) / dt);
    nu_hot = s.wall_heat_flow_k_m3_s(x_min) / alpha;
    nu_cold = -s.wall_heat_flow_k_m3_s(x_max) / alpha;
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    history.push_back({s.time_s(), wall_before + wall,
                       cpu_before + static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC,
                       nu_hot});
    if (rate < rate_tolerance && std::abs(nu_hot - nu_cold) < balance_tolerance * nu_hot) break;
    if (s.time_s() > 2000) break;  // not steady: reported below as such
  }
  const double cpu_s = cpu_before + static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  const double wall_s = history.back().wall_s;
  if (sequence) {
    sequence->cells = cells;
    sequence->temperature = s.temperature_c();
    for (int d = 0; d < 3; ++d) sequence->velocity[d] = s.velocity_m_s(d);
    sequence->wall_s = wall_s;
    sequence->cpu_s = cpu_s;
  }
  const Sample &s3 = settled(history, 1e-3), &s4 = settled(history, 1e-4);
  std::printf(
      "thaw cube %d^3%s  threads %d  steps %ld  t %.1f  wall %.2f s  cpu %.2f s  Nu hot %.5f "
      "cold %.5f  error %+.3f %%  max|dT/dt| %.1e  settled 1e-3 at t %.1f (%.2f cpu s, %.2f wall "
      "s), 1e-4 at t %.1f (%.2f cpu s, %.2f wall s)  %.3g cell steps/cpu s\n",
      cells, sequence && wall_before > 0 ? " (sequenced)" : "", threads, steps, s.time_s(), wall_s,
      cpu_s, nu_hot, nu_cold, 100 * (nu_hot - kTricNu1e5) / kTricNu1e5, rate, s3.time, s3.cpu_s,
      s3.wall_s, s4.time, s4.cpu_s, s4.wall_s,
      static_cast<double>(s.grid().cell_count()) * steps / cpu_s);
  std::fflush(stdout);
  return nu_hot;
}

}  // namespace

int main(int argc, char** argv) {
  const int threads = argc > 1 ? std::atoi(argv[1]) : 1;
  const double rate = argc > 2 ? std::atof(argv[2]) : 1e-5;
  const double balance = argc > 3 ? std::atof(argv[3]) : 1e-4;
  std::vector<int> grids;
  for (int a = 4; a < argc; ++a) grids.push_back(std::atoi(argv[a]));
  if (grids.empty()) grids = {16, 32};
  const char* sequencing = std::getenv("SEQUENCE");
  State state;
  State* sequence = sequencing && std::string(sequencing) == "1" ? &state : nullptr;
  std::vector<double> nu;
  for (int n : grids) nu.push_back(run(n, threads, rate, balance, sequence));
  if (nu.size() >= 2) {
    const double coarse = nu[nu.size() - 2], fine = nu.back();
    const double extrapolated = fine + (fine - coarse) / 3.0;
    std::printf("Richardson (%d^3, %d^3, order 2): Nu %.5f, error %+.3f %% (Tric et al. %.4f)\n",
                grids[grids.size() - 2], grids.back(), extrapolated,
                100 * (extrapolated - kTricNu1e5) / kTricNu1e5, kTricNu1e5);
  }
  return 0;
}
