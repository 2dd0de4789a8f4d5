#pragma once
// Sums and maxima over a grid that do not depend on the thread count: each row (j, k) is summed
// in index order into its own slot, in parallel, and the rows are then added in row order by one
// thread. OpenMP's reduction clause adds per-thread partials in an order that depends on the
// thread count, so its results differ in the last bits between 1 and 2 threads; this does not.
#include <algorithm>
#include <cmath>
#include <vector>

namespace thaw::sim::flow {

/// Sum over rows of row_sum(j, k) for j < ny, k < nz, thread-count independent.
template <class RowSum>
double ordered_row_sum(int ny, int nz, RowSum row_sum) {
  std::vector<double> rows(static_cast<std::size_t>(ny) * nz, 0.0);
#pragma omp parallel for collapse(2) schedule(static) if (rows.size() * 64 >= 8192)
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j) rows[static_cast<std::size_t>(j) + ny * k] = row_sum(j, k);
  double total = 0;
  for (double r : rows) total += r;
  return total;
}

}  // namespace thaw::sim::flow
