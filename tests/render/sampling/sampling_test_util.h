#pragma once
// Statistics shared by the sampling, light and film tests: the (0,m,2)-net check, chi-square
// critical values and the L2 star discrepancy.
#include <cmath>
#include <cstdint>
#include <vector>

#include "render/sampling/pixel_sampler.h"

namespace thaw::render::test {

/// Whether `pts` (2^m of them) form a (0,m,2)-net in base 2: for every split m = a + b, each of
/// the 2^a x 2^b elementary boxes [i/2^a, (i+1)/2^a) x [j/2^b, (j+1)/2^b) holds exactly one.
inline bool is_02_net(const std::vector<sampling::Point2>& pts, int m) {
  if (pts.size() != (std::size_t{1} << m)) return false;
  for (int a = 0; a <= m; ++a) {
    const int b = m - a;
    std::vector<int> count(std::size_t{1} << m, 0);
    for (const auto& p : pts) {
      const auto i = static_cast<std::size_t>(p.x * float(1 << a));
      const auto j = static_cast<std::size_t>(p.y * float(1 << b));
      if (++count[(i << b) | j] > 1) return false;
    }
  }
  return true;
}

/// Upper critical value of chi-square with k degrees of freedom at tail probability 1e-6 (the
/// Wilson-Hilferty cube approximation, accurate to < 1 % for k >= 10; z(1e-6) = 4.753).
inline double chi_square_critical_1e6(int k) {
  const double h = 2.0 / (9.0 * k);
  const double c = 1.0 - h + 4.753 * std::sqrt(h);
  return k * c * c * c;
}

/// Chi-square statistic of counts against equal expected counts.
inline double chi_square_uniform(const std::vector<int>& counts, double expected) {
  double chi2 = 0;
  for (int c : counts) chi2 += (c - expected) * (c - expected) / expected;
  return chi2;
}

/// Squared L2 star discrepancy of points in [0,1)^2 (Warnock 1972):
/// T^2 = 1/9 - (2/N) sum_i prod_k (1 - x_ik^2)/2 + (1/N^2) sum_ij prod_k (1 - max(x_ik, x_jk)).
/// For N independent uniform points its expectation is (1/4 - 1/9) / N.
inline double l2_star_discrepancy_squared(const std::vector<sampling::Point2>& pts) {
  const double n = double(pts.size());
  double s1 = 0, s2 = 0;
  for (const auto& p : pts) s1 += (1.0 - double(p.x) * p.x) * (1.0 - double(p.y) * p.y) / 4.0;
  for (const auto& p : pts)
    for (const auto& q : pts)
      s2 += (1.0 - std::max(double(p.x), double(q.x))) * (1.0 - std::max(double(p.y), double(q.y)));
  return 1.0 / 9.0 - 2.0 / n * s1 + s2 / (n * n);
}

}  // namespace thaw::render::test
