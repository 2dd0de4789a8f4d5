// The multigrid-preconditioned CG pressure solve (sim/flow/multigrid_pressure.h): recovers a
// known discrete solution on planar, axisymmetric and 3D boxes, and its iteration count does
// not grow with the grid (the point of multigrid).
#include "sim/flow/multigrid_pressure.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/flow/mac_grid.h"

namespace thaw::sim::flow {
namespace {

struct Poisson {
  MacGrid grid;
  std::array<std::vector<double>, 3> g;
};

Poisson make_poisson(FlowGeometry geometry, int n) {
  Poisson p;
  p.grid.geometry = geometry;
  p.grid.n = {n, n + n / 2, geometry == FlowGeometry::cartesian3d ? n : 1};
  p.grid.h_m = 1.0 / n;
  for (int d = 0; d < 3; ++d) {
    p.g[d].assign(p.grid.face_count(d), 0.0);
    if (d >= p.grid.dims()) continue;
    const auto f = p.grid.face_dims(d);
    for (int k = 0; k < f[2]; ++k)
      for (int j = 0; j < f[1]; ++j)
        for (int i = 0; i < f[0]; ++i) {
          const int along = d == 0 ? i : (d == 1 ? j : k);
          if (along > 0 && along < p.grid.n[d])
            p.g[d][p.grid.face(d, i, j, k)] = p.grid.face_area(d, i) / p.grid.h_m;
        }
  }
  return p;
}

/// b = L p for a smooth p, then solves L x = b from 0 and returns (iterations, max |x - p| after
/// removing the means).
std::pair<int, double> solve_known(FlowGeometry geometry, int n) {
  Poisson P = make_poisson(geometry, n);
  const MacGrid& g = P.grid;
  std::vector<double> exact(g.cell_count()), b(g.cell_count(), 0.0), x(g.cell_count(), 0.0);
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
        exact[g.cell(i, j, k)] = std::cos(std::numbers::pi * (i + 0.5) / g.n[0]) *
                                 std::cos(2 * std::numbers::pi * (j + 0.5) / g.n[1]) *
                                 (1.0 + 0.3 * std::sin(0.7 * k));
  // b = L exact
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const std::size_t c = g.cell(i, j, k);
        for (int d = 0; d < g.dims(); ++d) {
          int lo[3] = {i, j, k}, hi[3] = {i, j, k}, cl[3] = {i, j, k}, ch[3] = {i, j, k};
          ++hi[d];
          --cl[d];
          ++ch[d];
          const double gl = P.g[d][g.face(d, lo[0], lo[1], lo[2])];
          const double gh = P.g[d][g.face(d, hi[0], hi[1], hi[2])];
          if (gl > 0) b[c] += gl * (exact[c] - exact[g.cell(cl[0], cl[1], cl[2])]);
          if (gh > 0) b[c] += gh * (exact[c] - exact[g.cell(ch[0], ch[1], ch[2])]);
        }
      }
  MultigridPressureSolver solver;
  solver.set_operator(g.n, P.g);
  double bmax = 0;
  for (double v : b) bmax = std::max(bmax, std::abs(v));
  const PressureSolveReport r = solver.solve(b, x, 1e-11 * bmax);
  EXPECT_TRUE(r.converged);
  EXPECT_GT(solver.levels(), 2);
  double mx = 0, me = 0;
  for (std::size_t c = 0; c < x.size(); ++c) {
    mx += x[c];
    me += exact[c];
  }
  mx /= x.size();
  me /= x.size();
  double err = 0;
  for (std::size_t c = 0; c < x.size(); ++c)
    err = std::max(err, std::abs(x[c] - mx - exact[c] + me));
  return {r.iterations, err};
}

TEST(MultigridPressure, RecoversAKnownSolutionInFewIterations) {
  for (FlowGeometry geometry :
       {FlowGeometry::planar, FlowGeometry::axisymmetric, FlowGeometry::cartesian3d}) {
    const bool three = geometry == FlowGeometry::cartesian3d;
    const auto [it_coarse, err_coarse] = solve_known(geometry, three ? 8 : 32);
    const auto [it_fine, err_fine] = solve_known(geometry, three ? 32 : 128);
    std::printf("geometry %d: iterations %d -> %d, errors %.2e %.2e\n", static_cast<int>(geometry),
                it_coarse, it_fine, err_coarse, err_fine);
    // The residual is 1e-11 of b; the error is at most the condition number (~n^2) times that.
    EXPECT_LT(err_coarse, 1e-6);
    EXPECT_LT(err_fine, 1e-6);
    // Multigrid: the iteration count hardly grows over a 4x finer grid (CG alone: 4x more).
    EXPECT_LE(it_fine, it_coarse + 4);
    EXPECT_LE(it_fine, 20);
  }
}

}  // namespace
}  // namespace thaw::sim::flow
