// Multigrid-preconditioned conjugate gradients for the pressure (multigrid_pressure.h).
#include "sim/flow/multigrid_pressure.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "base/check.h"
#include "sim/flow/ordered_sum.h"

namespace thaw::sim::flow {
namespace {

using Level = MultigridPressureSolver::Level;

/// Loops over fewer cells run on one thread: a parallel region costs a barrier, which on a
/// loaded machine can wait for a descheduled thread far longer than the loop takes.
constexpr std::size_t kParallelCells = 8192;
bool kParallel(const std::array<int, 3>& n) {
  return static_cast<std::size_t>(n[0]) * n[1] * n[2] >= kParallelCells;
}

std::size_t cell_index(const std::array<int, 3>& n, int i, int j, int k) {
  return static_cast<std::size_t>(i) +
         static_cast<std::size_t>(n[0]) *
             (static_cast<std::size_t>(j) + static_cast<std::size_t>(n[1]) * k);
}
std::size_t face_index(const std::array<int, 3>& n, int d, int i, int j, int k) {
  std::array<int, 3> f = n;
  ++f[d];
  return static_cast<std::size_t>(i) +
         static_cast<std::size_t>(f[0]) *
             (static_cast<std::size_t>(j) + static_cast<std::size_t>(f[1]) * k);
}

/// The rows a cell row (j, k) sees: its own and its neighbours along y and z (a row of zeros
/// beyond the box, where the conductances are zero anyway).
struct Rows {
  const double *self, *ym, *yp, *zm, *zp;
};
inline Rows rows_of(const Level& L, const std::vector<double>& x, int j, int k) {
  const auto& n = L.n;
  const std::size_t sy = static_cast<std::size_t>(n[0]), sz = sy * n[1];
  const std::size_t row = cell_index(n, 0, j, k);
  const double* zero = L.zero.data();
  const double* self = x.data() + row;
  return {self, j > 0 ? self - sy : zero, j + 1 < n[1] ? self + sy : zero, k > 0 ? self - sz : zero,
          k + 1 < n[2] ? self + sz : zero};
}

/// sum over the faces of cell i of row r of g_f x_neighbour (c: the cell's index).
inline double neighbour_sum(const Level& L, const Rows& r, int i, std::size_t c) {
  double s = L.nb[2][c] * r.ym[i] + L.nb[3][c] * r.yp[i];
  if (L.n[2] > 1) s += L.nb[4][c] * r.zm[i] + L.nb[5][c] * r.zp[i];
  if (i > 0) s += L.nb[0][c] * r.self[i - 1];
  if (i + 1 < L.n[0]) s += L.nb[1][c] * r.self[i + 1];
  return s;
}

/// r = b - L x.
void residual(Level& L, const std::vector<double>& x, const std::vector<double>& b,
              std::vector<double>& r) {
  const auto n = L.n;
#pragma omp parallel for collapse(2) schedule(static) if (kParallel(n))
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j) {
      const Rows rows = rows_of(L, x, j, k);
      const std::size_t row = cell_index(n, 0, j, k);
      for (int i = 0; i < n[0]; ++i) {
        const std::size_t c = row + i;
        r[c] = b[c] - (L.diag[c] * x[c] - neighbour_sum(L, rows, i, c));
      }
    }
}

/// One Gauss-Seidel half sweep over the cells of one colour ((i + j + k) % 2 == colour).
void smooth_colour(Level& L, int colour) {
  const auto n = L.n;
#pragma omp parallel for collapse(2) schedule(static) if (kParallel(n))
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j) {
      const Rows rows = rows_of(L, L.x, j, k);
      const std::size_t row = cell_index(n, 0, j, k);
      for (int i = (j + k + colour) & 1; i < n[0]; i += 2) {
        const std::size_t c = row + i;
        L.x[c] = (L.b[c] + neighbour_sum(L, rows, i, c)) * L.inv_diag[c];
      }
    }
}

void compute_diagonal(Level& L) {
  const auto n = L.n;
  L.diag.assign(static_cast<std::size_t>(n[0]) * n[1] * n[2], 0.0);
  if (!L.mass.empty()) L.diag = L.mass;
  for (auto& v : L.nb) v.assign(L.diag.size(), 0.0);
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const std::size_t c = cell_index(n, i, j, k);
        double s = L.diag[c];
        for (int d = 0; d < 3; ++d) {
          int hi[3] = {i, j, k};
          ++hi[d];
          L.nb[2 * d][c] = L.g[d][face_index(n, d, i, j, k)];
          L.nb[2 * d + 1][c] = L.g[d][face_index(n, d, hi[0], hi[1], hi[2])];
          s += L.nb[2 * d][c] + L.nb[2 * d + 1][c];
        }
        L.diag[c] = s;
      }
  const std::size_t cells = L.diag.size();
  // a cell without conductance or mass is left alone by the smoother
  L.inv_diag.resize(cells);
  for (std::size_t c = 0; c < cells; ++c) L.inv_diag[c] = L.diag[c] > 0 ? 1.0 / L.diag[c] : 0.0;
  L.zero.assign(static_cast<std::size_t>(n[0]), 0.0);
  L.x.assign(cells, 0.0);
  L.b.assign(cells, 0.0);
  L.r.assign(cells, 0.0);
}

/// The coarse level of `fine`: 2 x 2 (x 2) children per cell along each axis with more than one
/// cell; a coarse face's conductance is the sum over the fine faces it covers divided by 2.
Level coarsen(const Level& fine) {
  Level c;
  for (int d = 0; d < 3; ++d) c.n[d] = fine.n[d] == 1 ? 1 : (fine.n[d] + 1) / 2;
  for (int d = 0; d < 3; ++d) {
    std::array<int, 3> f = c.n;
    ++f[d];
    c.g[d].assign(static_cast<std::size_t>(f[0]) * f[1] * f[2], 0.0);
    const int step[3] = {fine.n[0] == 1 ? 1 : 2, fine.n[1] == 1 ? 1 : 2, fine.n[2] == 1 ? 1 : 2};
    for (int K = 0; K < f[2]; ++K)
      for (int J = 0; J < f[1]; ++J)
        for (int I = 0; I < f[0]; ++I) {
          const int C[3] = {I, J, K};
          double s = 0;
          // fine faces: along d at exactly step*C[d]; across, the children step*C .. +step-1
          int lo[3], hi[3];
          for (int e = 0; e < 3; ++e) {
            lo[e] = step[e] * C[e];
            hi[e] = e == d ? lo[e] : std::min(lo[e] + step[e] - 1, fine.n[e] - 1);
          }
          if (lo[d] > fine.n[d]) continue;
          for (int k = lo[2]; k <= hi[2]; ++k)
            for (int j = lo[1]; j <= hi[1]; ++j)
              for (int i = lo[0]; i <= hi[0]; ++i) s += fine.g[d][face_index(fine.n, d, i, j, k)];
          c.g[d][face_index(c.n, d, I, J, K)] = 0.5 * s;
        }
  }
  if (!fine.mass.empty()) {  // P^T M P: the children's sum
    c.mass.assign(static_cast<std::size_t>(c.n[0]) * c.n[1] * c.n[2], 0.0);
    for (int k = 0; k < fine.n[2]; ++k)
      for (int j = 0; j < fine.n[1]; ++j)
        for (int i = 0; i < fine.n[0]; ++i)
          c.mass[cell_index(c.n, fine.n[0] == 1 ? i : i / 2, fine.n[1] == 1 ? j : j / 2,
                            fine.n[2] == 1 ? k : k / 2)] += fine.mass[cell_index(fine.n, i, j, k)];
  }
  compute_diagonal(c);
  return c;
}

int parent(const Level& fine, int d, int i) {
  return fine.n[d] == 1 ? i : i / 2;
}

}  // namespace

MultigridPressureSolver::MultigridPressureSolver(int sweeps, int max_iterations)
    : sweeps_(sweeps), max_iterations_(max_iterations) {}

void MultigridPressureSolver::set_operator(const std::array<int, 3>& cells,
                                           const std::array<std::vector<double>, 3>& g) {
  set_operator(cells, g, {});
}

void MultigridPressureSolver::set_operator(const std::array<int, 3>& cells,
                                           const std::array<std::vector<double>, 3>& g,
                                           const std::vector<double>& mass) {
  levels_.clear();
  Level top;
  top.n = cells;
  top.g = g;
  top.mass = mass;
  THAW_CHECK(
      mass.empty() || mass.size() == static_cast<std::size_t>(cells[0]) * cells[1] * cells[2],
      "operator: one mass per cell");
  for (int d = 0; d < 3; ++d)
    THAW_CHECK(top.g[d].size() == static_cast<std::size_t>(cells[0] + (d == 0)) *
                                      (cells[1] + (d == 1)) * (cells[2] + (d == 2)),
               "pressure operator: conductance array of the wrong size");
  compute_diagonal(top);
  levels_.push_back(std::move(top));
  // Coarsen while every axis in use keeps at least 2 cells.
  for (;;) {
    const Level& f = levels_.back();
    bool can = true;
    for (int d = 0; d < 3; ++d)
      if (f.n[d] > 1 && f.n[d] < 3) can = false;
    if (!can) break;
    levels_.push_back(coarsen(f));
  }
}

void MultigridPressureSolver::update_operator(const std::array<int, 3>& cells,
                                              const std::array<std::vector<double>, 3>& g,
                                              const std::vector<double>& mass) {
  if (levels_.empty() || levels_[0].n != cells || levels_[0].mass.empty() != mass.empty()) {
    set_operator(cells, g, mass);
    return;
  }
  Level& top = levels_[0];
  for (int d = 0; d < 3; ++d) {
    THAW_CHECK(g[d].size() == top.g[d].size(),
               "pressure operator: conductance array of the wrong size");
    top.g[d] = g[d];
  }
  THAW_CHECK(mass.size() == top.mass.size(), "operator: one mass per cell");
  top.mass = mass;
  compute_diagonal(top);
}

void MultigridPressureSolver::v_cycle(int l) {
  Level& L = levels_[l];
  std::fill(L.x.begin(), L.x.end(), 0.0);
  const bool coarsest = l + 1 == static_cast<int>(levels_.size());
  // Symmetric smoothing: (red, black)^s before, (black, red)^s after; the coarsest level is
  // smoothed long enough to act as its solve (it has 2 cells along an axis).
  const int pre = coarsest ? 20 : sweeps_;
  for (int s = 0; s < pre; ++s) {
    smooth_colour(L, 0);
    smooth_colour(L, 1);
  }
  if (!coarsest) {
    residual(L, L.x, L.b, L.r);
    Level& C = levels_[l + 1];
    std::fill(C.b.begin(), C.b.end(), 0.0);
    for (int k = 0; k < L.n[2]; ++k)
      for (int j = 0; j < L.n[1]; ++j)
        for (int i = 0; i < L.n[0]; ++i)
          C.b[cell_index(C.n, parent(L, 0, i), parent(L, 1, j), parent(L, 2, k))] +=
              L.r[cell_index(L.n, i, j, k)];
    v_cycle(l + 1);
#pragma omp parallel for collapse(2) schedule(static) if (kParallel(L.n))
    for (int k = 0; k < L.n[2]; ++k)
      for (int j = 0; j < L.n[1]; ++j)
        for (int i = 0; i < L.n[0]; ++i)
          L.x[cell_index(L.n, i, j, k)] +=
              C.x[cell_index(C.n, parent(L, 0, i), parent(L, 1, j), parent(L, 2, k))];
  }
  for (int s = 0; s < pre; ++s) {
    smooth_colour(L, 1);
    smooth_colour(L, 0);
  }
}

PressureSolveReport MultigridPressureSolver::solve(const std::vector<double>& b,
                                                   std::vector<double>& p, double tolerance) {
  THAW_CHECK(!levels_.empty(), "pressure solve before set_operator");
  Level& L = levels_[0];
  const std::size_t cells = L.diag.size();
  THAW_CHECK(b.size() == cells && p.size() == cells, "pressure solve: vector of the wrong size");
  const auto n = L.n;
  auto dot = [&](const std::vector<double>& a, const std::vector<double>& c) {
    return ordered_row_sum(n[1], n[2], [&](int j, int k) {
      double s = 0;
      const std::size_t row = cell_index(n, 0, j, k);
      for (int i = 0; i < n[0]; ++i) s += a[row + i] * c[row + i];
      return s;
    });
  };
  auto max_abs = [&](const std::vector<double>& a) {
    double m = 0;
    for (double v : a) m = std::max(m, std::abs(v));
    return m;
  };
  std::vector<double> r(cells), z(cells), d(cells), q(cells), zero(cells, 0.0);
  residual(L, p, b, r);
  PressureSolveReport report;
  report.residual_max = max_abs(r);
  if (report.residual_max <= tolerance) {
    report.converged = true;
    return report;
  }
  auto precondition = [&](const std::vector<double>& in, std::vector<double>& out) {
    L.b = in;
    v_cycle(0);
    out = L.x;
  };
  precondition(r, z);
  d = z;
  double rz = dot(r, z);
  for (int it = 1; it <= max_iterations_; ++it) {
    residual(L, d, zero, q);  // q = -L d
    const double dq = -dot(d, q);
    if (!(dq > 0)) break;
    const double alpha = rz / dq;
#pragma omp parallel for schedule(static) if (cells >= kParallelCells)
    for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t>(cells); ++c) {
      p[c] += alpha * d[c];
      r[c] += alpha * q[c];
    }
    report.iterations = it;
    report.residual_max = max_abs(r);
    if (report.residual_max <= tolerance) {
      report.converged = true;
      break;
    }
    precondition(r, z);
    const double rz_new = dot(r, z);
    const double beta = rz_new / rz;
    rz = rz_new;
#pragma omp parallel for schedule(static) if (cells >= kParallelCells)
    for (std::ptrdiff_t c = 0; c < static_cast<std::ptrdiff_t>(cells); ++c)
      d[c] = z[c] + beta * d[c];
  }
  return report;
}

}  // namespace thaw::sim::flow
