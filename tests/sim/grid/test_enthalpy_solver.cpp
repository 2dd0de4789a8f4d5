// The grid enthalpy solver (sim/grid/enthalpy_solver.h) against exact answers: the planar
// two-phase Neumann problem run inside the 3D and the axisymmetric grids (front position and
// its observed order); the same at small and large Stefan numbers, melting and freezing, with the
// heat through the held face checked against the exact solution's gradient and the energy
// balance; the same slab along x, y and z. Symmetry and thread counts: test_grid_runs.cpp.
#include "sim/grid/enthalpy_solver.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstdio>

#include "sim/format/scenario_file.h"
#include "sim/reference/neumann.h"
#include "tests/sim/grid/planar_neumann_grid.h"

namespace thaw::sim {
namespace {

/// Freezing Neumann problem: ice grows from a wall held at -20 C into water at +5 C. Freezing
/// (not melting) because the far field is then the slowly diffusing water, so a short domain
/// (4.5 front lengths) contains the whole thermal layer: at the far wall the exact solution
/// differs from the far temperature by erfc(3) ~ 2e-5 of the jump.
struct NeumannCase {
  Materials mat = default_materials();
  NeumannSolution exact;
  double t0 = 100, t1 = 400, length = 0;
  NeumannCase() {
    exact = solve_neumann(mat.ice_conductivity_w_mk, mat.ice_heat_capacity(),
                          mat.water_conductivity_w_mk, mat.water_heat_capacity(),
                          mat.latent_heat_per_volume(), -20.0, mat.melting_point_c, 5.0);
    length = exact.front(t1) + 6.0 * std::sqrt(exact.alpha2() * t1);
  }
  /// Cell average of the exact enthalpy over [a, b] (Gauss-Legendre, 8 points per sub-interval,
  /// the front's cell split at the front so the latent jump is integrated exactly).
  double cell_enthalpy(double a, double b) const {
    const double s = exact.front(t0);
    auto integrate = [&](double lo, double hi) {
      static const double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                  0.9602898564975363};
      static const double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                  0.1012285362903763};
      double sum = 0;
      for (int q = 0; q < 4; ++q)
        for (int sign : {-1, 1}) {
          const double xx = 0.5 * (lo + hi) + sign * 0.5 * (hi - lo) * x[q];
          sum += w[q] * enthalpy_of_temperature(mat, exact.temperature(xx, t0), xx > s);
        }
      return 0.5 * sum * (hi - lo);
    };
    if (s > a && s < b) return (integrate(a, s) + integrate(s, b)) / (b - a);
    return integrate(a, b) / (b - a);
  }
  /// The problem along axis `axis` (0 = x/r, 1 = y) of an n-cell line, `across` cells across.
  GridProblem problem(GridField::Geometry g, int n, int across, double dt) const {
    GridProblem p;
    p.geometry = g;
    p.spacing_m = length / n;
    p.cells = {across, n, g == GridField::Geometry::axisymmetric ? 1 : across};
    p.materials = mat;
    p.drain = false;
    p.fixed_step_s = dt;
    p.walls[2] = {true, exact.face_temperature};
    p.walls[3] = {true, exact.far_temperature};
    const std::size_t cells = static_cast<std::size_t>(p.cells[0]) * p.cells[1] * p.cells[2];
    p.material_fraction.assign(cells, 1.0);
    p.enthalpy_j_m3.resize(cells);
    for (std::size_t c = 0; c < cells; ++c) {
      const int j = static_cast<int>((c / p.cells[0]) % p.cells[1]);
      p.enthalpy_j_m3[c] = cell_enthalpy(j * p.spacing_m, (j + 1) * p.spacing_m);
    }
    return p;
  }
};

/// Front position = ice volume / cross-section (the sub-cell reconstruction from fractions).
double run_front(const NeumannCase& nc, GridField::Geometry g, int n, double dt,
                 double* energy_error = nullptr) {
  const int across = 2;
  EnthalpySolver solver(nc.problem(g, n, across, dt));
  // the solver's clock starts at 0: run for t1 - t0
  solver.advance_to(nc.t1 - nc.t0);
  const GridSnapshot snap = solver.snapshot();
  double area = 0;
  for (int i = 0; i < across; ++i)
    for (int k = 0; k < (g == GridField::Geometry::axisymmetric ? 1 : across); ++k)
      area += solver.cell_volume(i, 0, k) / (nc.length / n);
  if (energy_error) *energy_error = solver.statistics().max_step_energy_error;
  return snap.ice_volume_m3 / area;
}

void expect_order(GridField::Geometry g) {
  const NeumannCase nc;
  const double exact = nc.exact.front(nc.t1);
  std::vector<double> errors;
  int n = 32;
  for (int level = 0; level < 3; ++level, n *= 2) {
    const double dx = nc.length / n;
    const double dt = 0.25 * dx * dx / nc.exact.alpha1();
    double energy_error = 0;
    const double front = run_front(nc, g, n, dt, &energy_error);
    errors.push_back(std::abs(front - exact));
    std::printf("%s n=%d dx=%.3g dt=%.3g front=%.9g exact=%.9g err=%.3g energy=%.2g\n",
                to_string(g), n, dx, dt, front, exact, errors.back(), energy_error);
    EXPECT_LT(energy_error, 1e-8);  // the per-step energy requirement
  }
  // dt ~ dx^2, so the time error is of second order in dx and the spatial order shows.
  const double order =
      std::log2(errors.front() / errors.back()) / static_cast<double>(errors.size() - 1);
  std::printf("%s: observed order of the front %.3f\n", to_string(g), order);
  // The issue asks >= 1 with 1.5 as the target. Measured 1.59 with the sub-cell front
  // conductance (enthalpy_solver.cpp, face_conductance_per_area; 1.03 without it, the plain
  // enthalpy method's first order); the errors fall 2.9x and 3.1x per halving here.
  EXPECT_GE(order, 1.5);
  EXPECT_LT(errors.back(), 0.5 * nc.length / (n / 2));  // below half a cell at the finest grid
}

TEST(EnthalpySolver, NeumannFrontOrder3d) {
  expect_order(GridField::Geometry::cartesian3d);
}
TEST(EnthalpySolver, NeumannFrontOrderAxisymmetric) {
  expect_order(GridField::Geometry::axisymmetric);
}

// --- the planar Neumann problem at other Stefan numbers, melting and freezing ----------------
// (tests/sim/grid/planar_neumann_grid.h; the full set, with the far-field layers of two-phase
// problems that need longer grids, is in test_enthalpy_solver_e2e.cpp.) The front is resolved by
// 8, 16 and 32 cells at t1; its error is the largest over 16 instants (the enthalpy method's
// error oscillates as the front crosses cells). What is asserted, and why:
//  * front: the scheme is second order where the phase is pure and first order in the cell
//    holding the front, whose effect on the front position partly cancels as the front crosses
//    cells; the sub-cell front conductance makes it 1.5-2 (docs/validation.md). Asserted: the
//    issue's target 1.5 on the mean order of the two refinements and its minimum 1 on each.
//  * heat: the heat that entered through the held face, from the solver, against the exact
//    solution's face gradient integrated over [t0, t1] (test's own finite differences and
//    quadrature, not the solver's numbers nor NeumannSolution's closed-form flux). The total
//    enthalpy is the integral of a field that is second-order accurate except in one cell per
//    front, so the same bars as the front.
//  * conservation: the solver's heat equals its own enthalpy change (sensible + latent) to
//    round-off, 1e-12 of the heat; per step the 1e-8 (measured ~1e-15).
//  * the reference itself: exact heat and exact enthalpy change agree to 1e-6 (quadrature and
//    finite differences ~1e-8; the far wall's heat is counted on both sides).
void expect_study(const test::PlanarNeumann& pn, GridField::Geometry g) {
  const test::NeumannStudy st = test::study_planar_neumann(pn, g);
  using S = test::NeumannStudy;
  EXPECT_LT(st.exact_identity, 1e-6) << pn.name;
  EXPECT_GE(S::order(st.front), 1.5) << pn.name;
  EXPECT_GE(S::pair_order(st.front, 0), 1.0) << pn.name;
  EXPECT_GE(S::pair_order(st.front, 1), 1.0) << pn.name;
  EXPECT_GE(S::order(st.heat), 1.5) << pn.name;
  EXPECT_GE(S::pair_order(st.heat, 0), 1.0) << pn.name;
  EXPECT_GE(S::pair_order(st.heat, 1), 1.0) << pn.name;
  EXPECT_LT(st.heat_vs_enthalpy, 1e-12) << pn.name;
  EXPECT_LT(st.step_energy, 1e-8) << pn.name;
}

/// The cases whose far phase is at T_m (short grids: the unit-test subset).
std::vector<test::PlanarNeumann> short_cases() {
  const Materials d = default_materials();
  return {
      // small Stefan number: freezing from -1 C into water at T_m (St 0.006, lambda 0.055)
      {"freeze -1|0 (St 0.006)", d, false, -1, 0},
      // melting from +10 C into ice at T_m (St_water 0.14)
      {"melt +10|0 (St 0.14)", d, true, 10, 0},
      // large Stefan number: melting from +150 C into ice at T_m (St_water 2.05, lambda 0.81)
      {"melt +150|0 (St 2.05)", d, true, 150, 0},
  };
}

TEST(EnthalpySolver, NeumannStefanNumbersMeltingAndFreezingAxisymmetric) {
  for (const test::PlanarNeumann& pn : short_cases())
    expect_study(pn, GridField::Geometry::axisymmetric);
}
TEST(EnthalpySolver, NeumannStefanNumbersMeltingAndFreezing3d) {
  for (const test::PlanarNeumann& pn : short_cases())
    expect_study(pn, GridField::Geometry::cartesian3d);
}

TEST(EnthalpySolver, TheSameSlabAlongXYAndZGivesTheSameAnswer) {
  // The two-phase freezing problem along each axis of the 3D grid, 2 x 2 cells across: the three
  // runs do the same arithmetic on permuted cells except the order of the terms in each cell's
  // sum (stencil order x, y, z) and of the CG's block sums, so they agree to round-off: the CG
  // stops at a relative residual, and a few hundred steps of ~1e-15 relative differences stay
  // below 1e-11 of L_v. An axis mixed up anywhere (an area, a stride, a wall index) is O(1).
  const Materials d = default_materials();
  const test::PlanarNeumann pn("freeze -20|+5", d, false, -20, 5);
  const int n = 48;
  const double dx = pn.length / n, dt = 0.25 * dx * dx / pn.exact.alpha1();
  std::vector<std::vector<double>> fields;
  for (int axis : {0, 1, 2})
    fields.push_back(test::run_planar_neumann(pn, GridField::Geometry::cartesian3d, axis, n, 2, dt)
                         .final_enthalpy);
  // cell (c along the slab's axis, u, v across) of the run along `axis`
  auto at = [&](int axis, int c, int u, int v) {
    int ijk[3];
    ijk[axis] = c;
    ijk[axis == 0 ? 1 : 0] = u;
    ijk[axis == 2 ? 1 : 2] = v;
    const int nx = axis == 0 ? n : 2, ny = axis == 1 ? n : 2;
    return fields[axis][ijk[0] + nx * (ijk[1] + ny * ijk[2])];
  };
  const double latent = d.latent_heat_per_volume();
  double worst = 0, spread = 0;
  for (int c = 0; c < n; ++c)
    for (int u = 0; u < 2; ++u)
      for (int v = 0; v < 2; ++v) {
        worst = std::max({worst, std::abs(at(0, c, u, v) - at(1, c, u, v)) / latent,
                          std::abs(at(2, c, u, v) - at(1, c, u, v)) / latent});
        spread = std::max(spread, std::abs(at(1, c, u, v) - at(1, 0, 0, 0)) / latent);
      }
  std::printf("x, y, z runs differ by at most %.2e L_v\n", worst);
  EXPECT_LT(worst, 1e-11);
  EXPECT_GT(spread, 0.5);  // the field is not trivial: ice and water along the slab
}

TEST(EnthalpySolver, SteadyConductionThroughAConvectiveSurfaceIsExact) {
  // An ice slab (no phase change: everything stays below T_m) between a wall held at -20 C and
  // its surface, a cell face, under air at -5 C through h = 100 W/(m^2 K). At steady state the
  // temperature is linear, T(y) = T_wall + q y / k with q = (T_air - T_wall) / (L / k + 1 / h),
  // and every two-point flux of the scheme (half a cell to the wall, whole cells inside, half a
  // cell in series with the film at the surface) is exact for a linear profile: the discrete
  // steady state is the exact one at the cell centres, to the CG tolerance (measured 1.5e-7 K).
  // The slowest transient mode decays at least as fast as with an insulated surface, at
  // (pi / 2)^2 alpha / L^2 = 1 / (34 s): after 1000 s it is e^-29 of the initial 10 K. Before the
  // surface's half cell was put in series with the film, the surface sat at the cell centre: the
  // flux was too large by the half cell's resistance and the profile off by up to 0.044 K.
  const Materials mat = default_materials();
  const int layers = 16, n = layers + 4;
  const double length = 0.01, s = length / layers, t_wall = -20, t_air = -5, film = 100;
  GridProblem p;
  p.geometry = GridField::Geometry::cartesian3d;
  p.cells = {1, n, 1};
  p.spacing_m = s;
  p.materials = mat;
  p.material_fraction.assign(n, 0.0);
  p.enthalpy_j_m3.assign(n, 0.0);
  for (int j = 0; j < layers; ++j) {
    p.material_fraction[j] = 1;
    p.enthalpy_j_m3[j] = enthalpy_of_temperature(mat, -10, false);
  }
  p.walls[2] = {true, t_wall};
  p.surface_kind = OuterBoundary::convective;
  p.surface_temperature_c = t_air;
  p.heat_transfer_coefficient_w_m2k = film;
  p.drain = false;
  EnthalpySolver solver(p);
  solver.advance_to(1000);
  const double k = mat.ice_conductivity_w_mk;
  const double q = (t_air - t_wall) / (length / k + 1 / film);
  double worst = 0;
  for (int j = 0; j < layers; ++j) {
    const double t = mat.melting_point_c + solver.enthalpy()[j] / mat.ice_heat_capacity();
    worst = std::max(worst, std::abs(t - (t_wall + q * (j + 0.5) * s / k)));
  }
  std::printf(
      "steady slab: q = %.6g W/m^2, largest |T - T_exact| %.2e K (half-cell shift %.3f K)\n", q,
      worst, q * 0.5 * s / k);
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace thaw::sim
