#pragma once
// The grid solver's mesh: a uniform grid of cubic cells (axisymmetric (r, y) rings, full
// revolution, or 3D Cartesian boxes), with each cell's volume and face areas, and the loops
// that every part of the solver shares: over fixed blocks of cells (the unit of the
// deterministic parallel sums, block_team.h) and over a cell's face neighbours in a fixed
// order. Knows nothing of the physics, of files or of TOML.
#include <algorithm>
#include <array>
#include <vector>

#include "sim/grid/grid_field.h"

namespace thaw::sim {

/// Cells per block of the deterministic sums: partial sums of fixed blocks added in order, so
/// results do not depend on the thread count.
inline constexpr long kBlock = 4096;
/// Below this many cells a step runs on one thread (the barriers would cost more than the work).
inline constexpr long kParallelCells = 16384;

/// Sum of f(c) over the n cells by fixed blocks added in order (the same bits as the solver's
/// parallel block sums). Serial: a per-step reduction is too little work for a parallel region.
template <class F>
double sum_cells(long n, F&& f) {
  double total = 0;
  for (long b = 0; b * kBlock < n; ++b) {
    double s = 0;
    const long end = std::min(n, (b + 1) * kBlock);
    for (long c = b * kBlock; c < end; ++c) s += f(c);
    total += s;
  }
  return total;
}

/// Sum of the values in order.
inline double ordered_sum(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s;
}
/// Largest value, at least 0.
inline double largest(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, x);
  return m;
}

struct GridMesh {
  /// `cells`, `origin_m`, `dx_m` as GridField's. THAW_CHECK on an empty grid or an
  /// axisymmetric grid with more than one cell in z.
  GridMesh(GridField::Geometry geometry, std::array<int, 3> cells, std::array<double, 3> origin_m,
           double dx_m);

  int nx = 0, ny = 0, nz = 0;
  long n = 0;  ///< cells
  bool axisymmetric = false;
  std::array<double, 3> origin_m{0, 0, 0};
  double dx_m = 0;             ///< cell edge [m]
  std::vector<double> vol;     ///< cell volume [m^3] (full revolution when axisymmetric)
  std::vector<double> area_x;  ///< area of the face between i and i+1 (per i) [m^2]
  std::vector<double> area_y;  ///< area of a y face (per i) [m^2]
  double area_z = 0;           ///< area of a z face [m^2]

  long nxy() const { return static_cast<long>(nx) * ny; }
  /// Cell centre [m] (axisymmetric: {r, y, 0}).
  std::array<double, 3> centre(long c) const;

  long block_count() const { return (n + kBlock - 1) / kBlock; }
  long block_end(long bl) const { return std::min(n, (bl + 1) * kBlock); }
  /// f(c, i, j, k) for the cells c of block bl in order, with their grid indices kept by
  /// counting (three integer divisions per block instead of per cell).
  template <class F>
  void for_cells(long bl, F&& f) const {
    long c = bl * kBlock;
    const long end = block_end(bl), row = c / nx;
    int i = static_cast<int>(c % nx), j = static_cast<int>(row % ny),
        k = static_cast<int>(row / ny);
    for (; c < end; ++c) {
      f(c, i, j, k);
      if (++i == nx) {
        i = 0;
        if (++j == ny) {
          j = 0;
          ++k;
        }
      }
    }
  }
  /// f(nb) for the face neighbours of cell c (at i, j, k) in a fixed order.
  template <class F>
  void for_neighbours(long c, int i, int j, int k, F&& f) const {
    const long nxy_ = nxy();
    if (i > 0) f(c - 1);
    if (i + 1 < nx) f(c + 1);
    if (j > 0) f(c - nx);
    if (j + 1 < ny) f(c + nx);
    if (k > 0) f(c - nxy_);
    if (k + 1 < nz) f(c + nxy_);
  }
  template <class F>
  void for_neighbours(long c, F&& f) const {
    for_neighbours(c, static_cast<int>(c % nx), static_cast<int>((c / nx) % ny),
                   static_cast<int>(c / nxy()), f);
  }
};

}  // namespace thaw::sim
