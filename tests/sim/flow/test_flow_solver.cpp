// The Boussinesq MAC solver (sim/flow/flow_solver.h): divergence-free to the pressure solve's
// tolerance, energy conserved to rounding (change = wall heat), temperatures bounded, results
// identical for 1 and 2 threads (planar, axisymmetric, 3D), a stably stratified fluid at rest
// stays at rest, a cell of infinite drag holds still, and the cavity's centro-symmetry.
// The cavity's Nusselt numbers: test_cavity.cpp.
#include "sim/flow/flow_solver.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>

#include "tests/sim/flow/cavity.h"

namespace thaw::sim::flow {
namespace {

/// A box of water in `geometry`, a warm blob in 2 C water (the density maximum between them),
/// walls adiabatic except x_max held at 1 C.
FlowProblem water_box(FlowGeometry geometry, int n) {
  FlowProblem p;
  p.grid.geometry = geometry;
  p.grid.n = {n, n, geometry == FlowGeometry::cartesian3d ? n : 1};
  p.grid.h_m = 0.01 / n;  // a 1 cm box
  p.thermal_diffusivity_m2_s = 1.34e-7;
  p.walls[x_max] = {WallCondition::Kind::temperature, 1.0};
  return p;
}

void warm_blob(FlowSolver& s) {
  const MacGrid& g = s.grid();
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const double x = (i + 0.5) / g.n[0], y = (j + 0.5) / g.n[1];
        const double z = g.n[2] > 1 ? (k + 0.5) / g.n[2] - 0.5 : 0.0;
        const double r2 = (x - 0.3) * (x - 0.3) + (y - 0.4) * (y - 0.4) + z * z;
        s.temperature_c()[g.cell(i, j, k)] = 2.0 + 10.0 * std::exp(-r2 / 0.02);
      }
}

double sum_abs_content(const FlowSolver& s) {
  const MacGrid& g = s.grid();
  double e = 0;
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
        e += g.cell_volume(i) * std::abs(s.temperature_c()[g.cell(i, j, k)]);
  return e;
}

TEST(FlowSolver, DivergenceFreeEnergyConservedAndBounded) {
  for (FlowGeometry geometry :
       {FlowGeometry::planar, FlowGeometry::axisymmetric, FlowGeometry::cartesian3d}) {
    const int n = geometry == FlowGeometry::cartesian3d ? 12 : 24;
    FlowSolver s(water_box(geometry, n));
    warm_blob(s);
    const double t_min = 1.0, t_max = 12.0;  // the blob's range and the held wall
    double largest_relative_mismatch = 0, largest_divergence = 0;
    for (int step = 0; step < 40; ++step) {
      const double e0 = s.thermal_content_k_m3();
      const FlowStepReport r = s.step(s.stable_time_step_s());
      const double e1 = s.thermal_content_k_m3();
      largest_relative_mismatch = std::max(
          largest_relative_mismatch, std::abs(e1 - e0 - r.wall_heat_k_m3) / sum_abs_content(s));
      // The projection leaves a net outflow of at most pressure_tolerance * the largest face
      // flow in each cell: |div u| <= tol * max|u| A_max / V_min.
      const MacGrid& g = s.grid();
      double area_max = 0;
      for (int i = 0; i <= g.n[0]; ++i) area_max = std::max(area_max, g.face_area(0, i));
      for (int i = 0; i < g.n[0]; ++i) area_max = std::max(area_max, g.face_area(1, i));
      double u_max = 0;
      for (int d = 0; d < g.dims(); ++d)
        for (double u : s.velocity_m_s(d)) u_max = std::max(u_max, std::abs(u));
      const double bound =
          2.0 * s.problem().pressure_tolerance * u_max * area_max / g.cell_volume(0);
      largest_divergence = std::max(largest_divergence, s.max_divergence_per_s() / bound);
    }
    const auto [lo, hi] = std::minmax_element(s.temperature_c().begin(), s.temperature_c().end());
    std::printf(
        "geometry %d: energy mismatch %.2e, divergence / bound %.2e, T in [%.4f, %.4f], "
        "speed %.3g mm/s\n",
        static_cast<int>(geometry), largest_relative_mismatch, largest_divergence, *lo, *hi,
        1e3 * s.max_speed_m_s());
    // Rounding only: the fluxes telescope (~1e-16 per cell and step, summed over the cells).
    EXPECT_LT(largest_relative_mismatch, 1e-12);
    EXPECT_LE(largest_divergence, 1.0);
    // Koren's limiter with the SSP scheme at Courant <= 1/2: no new extrema.
    EXPECT_GE(*lo, t_min - 1e-12);
    EXPECT_LE(*hi, t_max + 1e-12);
    EXPECT_GT(s.max_speed_m_s(), 1e-5);  // the blob does move
  }
}

TEST(FlowSolver, SameResultForOneAndTwoThreads) {
  for (FlowGeometry geometry :
       {FlowGeometry::planar, FlowGeometry::axisymmetric, FlowGeometry::cartesian3d}) {
    const int n = geometry == FlowGeometry::cartesian3d ? 12 : 24;
    std::array<std::vector<double>, 4> runs[2];
    for (int threads : {1, 2}) {
      omp_set_num_threads(threads);
      FlowSolver s(water_box(geometry, n));
      warm_blob(s);
      for (int step = 0; step < 20; ++step) s.step(s.stable_time_step_s());
      runs[threads - 1] = {s.temperature_c(), s.velocity_m_s(0), s.velocity_m_s(1),
                           s.grid().dims() == 3 ? s.velocity_m_s(2) : std::vector<double>{}};
    }
    omp_set_num_threads(2);
    for (int f = 0; f < 4; ++f) EXPECT_TRUE(runs[0][f] == runs[1][f]) << "field " << f;
  }
}

TEST(FlowSolver, StableStratificationStaysAtRest) {
  // Linear fluid warmer upwards: hydrostatic, the pressure takes the buoyancy; nothing moves.
  FlowProblem p = test::cavity_problem(1e5, 0.71, 24);
  p.walls[x_min] = p.walls[x_max] = {};
  p.grid.geometry = FlowGeometry::axisymmetric;
  FlowSolver s(p);
  for (int j = 0; j < 24; ++j)
    for (int i = 0; i < 24; ++i) s.temperature_c()[s.grid().cell(i, j, 0)] = (j + 0.5) / 24 - 0.5;
  for (int step = 0; step < 50; ++step) s.step(s.stable_time_step_s());
  // The buoyancy is a discrete gradient of a cell field, which the projection removes to its
  // tolerance; the speed is that tolerance times the free-fall speed (1).
  EXPECT_LT(s.max_speed_m_s(), 1e-8);
}

TEST(FlowSolver, InfiniteDragHoldsCellsStill) {
  FlowProblem p = test::cavity_problem(1e5, 0.71, 32);
  FlowSolver s(p);
  // A vertical plate of "ice" in the middle two columns.
  std::vector<double> drag(s.grid().cell_count(), 0.0);
  for (int j = 0; j < 32; ++j)
    for (int i = 15; i <= 16; ++i) drag[s.grid().cell(i, j, 0)] = 1e12;
  s.set_drag_per_s(drag);
  for (int step = 0; step < 200; ++step) s.step(s.stable_time_step_s());
  double inside = 0, outside = 0;
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) {
      const double speed =
          std::hypot(s.cell_velocity_m_s(0, i, j, 0), s.cell_velocity_m_s(1, i, j, 0));
      (i == 15 || i == 16 ? inside : outside) =
          std::max(i == 15 || i == 16 ? inside : outside, speed);
    }
  std::printf("largest speed: in the plate %.3g, beside it %.3g\n", inside, outside);
  EXPECT_GT(outside, 1e-2);  // the two half cavities convect
  // Faces inside the plate: u / (1 + dt D), dt D ~ 1e10: still to 1e-9 of the flow beside it
  // (the plate's edge faces carry half the drag of a neighbour's mean).
  EXPECT_LT(inside, 1e-6 * outside);
}

TEST(FlowSolver, CavityStaysCentroSymmetric) {
  // Rotating the cavity by 180 degrees and flipping T maps the problem onto itself; the solver
  // keeps that to rounding (the red-black smoother and the limiter are symmetric).
  FlowSolver s(test::cavity_problem(1e5, 0.71, 32));
  for (int step = 0; step < 300; ++step) s.step(s.stable_time_step_s());
  const MacGrid& g = s.grid();
  double worst = 0;
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i)
      worst = std::max(worst, std::abs(s.temperature_c()[g.cell(i, j, 0)] +
                                       s.temperature_c()[g.cell(31 - i, 31 - j, 0)]));
  std::printf("centro-symmetry defect %.3g\n", worst);
  EXPECT_LT(worst, 1e-9);
}

}  // namespace
}  // namespace thaw::sim::flow
