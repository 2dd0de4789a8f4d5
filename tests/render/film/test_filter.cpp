#include "render/film/filter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/render/sampling/sampling_test_util.h"

namespace thaw::render {
namespace {

/// Integral of g(x) f1(x) over [-r, r] by Simpson's rule on 20000 intervals (error ~1e-12 for
/// these piecewise-smooth filters, whose kinks lie on the grid).
template <class G>
double integrate(const Filter& f, G g) {
  const int n = 20000;
  const double r = f.radius(), h = 2 * r / n;
  double s = 0;
  for (int i = 0; i <= n; ++i) {
    const double x = -r + i * h;
    s += (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0)) * g(x) * f.evaluate_1d(float(x));
  }
  return s * h / 3;
}

TEST(Filter, NamesAndDefaults) {
  EXPECT_EQ(filter_kind_from_name("box"), FilterKind::box);
  EXPECT_EQ(filter_kind_from_name("gaussian"), FilterKind::gaussian);
  EXPECT_EQ(filter_kind_from_name("mitchell"), FilterKind::mitchell);
  EXPECT_FALSE(filter_kind_from_name("lanczos"));
  EXPECT_FALSE(filter_kind_from_name("Box"));
  for (FilterKind k : {FilterKind::box, FilterKind::gaussian, FilterKind::mitchell})
    EXPECT_EQ(filter_kind_from_name(filter_name(k)), k);
  EXPECT_EQ(default_filter_radius(FilterKind::box), 0.5);
}

TEST(Filter, ShapesHaveTheirDefiningValues) {
  const Filter g(FilterKind::gaussian, 1.5), m(FilterKind::mitchell, 2.0);
  EXPECT_FLOAT_EQ(g.evaluate_1d(1.5f), 0.0f);  // shifted to reach 0 at the radius
  EXPECT_FLOAT_EQ(g.evaluate_1d(0.0f), float(1.0 - std::exp(-4.5)));
  EXPECT_EQ(g.evaluate_1d(1.6f), 0.0f);
  // Mitchell-Netravali, B = C = 1/3: f(0) = (6 - 2B) / 6, f(1) = B / 6 (eq. 8), negative lobe
  // between 1 and 2 (in units of r / 2), 0 at 2.
  EXPECT_FLOAT_EQ(m.evaluate_1d(0.0f), float((6.0 - 2.0 / 3.0) / 6.0));
  EXPECT_NEAR(m.evaluate_1d(1.0f), 1.0 / 18.0, 1e-7);
  EXPECT_LT(m.evaluate_1d(1.5f), 0.0f);
  EXPECT_NEAR(m.evaluate_1d(2.0f), 0.0, 1e-7);
  EXPECT_EQ(m.evaluate(0.0f, 3.0f), 0.0f);
}

TEST(Filter, GaussianTableFollowsTheFormula) {
  // Linear interpolation between 1025 nodes on [0, r]: error <= 9 / (8 * 1024^2) = 1.07e-6 (see
  // filter.cpp), plus float rounding of values <= 1.
  for (const double r : {0.5, 1.5, 4.0}) {
    const Filter g(FilterKind::gaussian, r);
    double worst = 0.0;
    for (int i = -20000; i <= 20000; ++i) {
      const double x = r * i / 20000.0;
      worst = std::max(worst, std::abs(double(g.evaluate_1d(float(x))) - g.gaussian_1d(x)));
    }
    EXPECT_LE(worst, 9.0 / (8.0 * 1024.0 * 1024.0) + 2e-7) << r;
    EXPECT_EQ(g.evaluate_1d(float(r) * 1.01f), 0.0f);
  }
}

TEST(Filter, BoxSamplesTheSquareUniformlyWithUnitWeight) {
  const Filter box(FilterKind::box, 0.5);
  const FilterSample s = box.sample({0.25f, 0.75f});
  EXPECT_FLOAT_EQ(s.dx, -0.25f);
  EXPECT_FLOAT_EQ(s.dy, 0.25f);
  EXPECT_EQ(s.weight, 1.0f);
}

TEST(Filter, ImportanceSampledWeightsReproduceTheFiltersMoments) {
  // E[w] = 1 and E[w dx^2] = int x^2 f1 / int f1 (f separable): the importance-sampled mean is
  // the filter's weighted average. 4096 net points; tolerance 5 standard errors of the samples.
  for (auto [kind, r] :
       {std::pair{FilterKind::gaussian, 1.5}, std::pair{FilterKind::gaussian, 3.0},
        std::pair{FilterKind::mitchell, 2.0}, std::pair{FilterKind::mitchell, 1.0}}) {
    const Filter f(kind, r);
    const double norm = integrate(f, [](double) { return 1.0; });
    const double second = integrate(f, [](double x) { return x * x; }) / norm;
    const sampling::PixelSampler sampler(1, 2);
    const int n = 4096;
    double w = 0, w2 = 0, m = 0, m2 = 0;
    for (int i = 0; i < n; ++i) {
      const FilterSample s = f.sample(sampler.get_2d(static_cast<std::uint32_t>(i), 0));
      ASSERT_LE(std::abs(s.dx), f.radius());
      ASSERT_LE(std::abs(s.dy), f.radius());
      w += s.weight;
      w2 += double(s.weight) * s.weight;
      const double v = s.weight * double(s.dx) * s.dx;
      m += v;
      m2 += v * v;
    }
    const double se_w = std::sqrt(std::max(0.0, w2 / n - (w / n) * (w / n)) / n);
    const double se_m = std::sqrt(std::max(0.0, m2 / n - (m / n) * (m / n)) / n);
    EXPECT_NEAR(w / n, 1.0, 5 * se_w + 1e-5) << filter_name(kind) << " " << r;
    EXPECT_NEAR(m / n, second, 5 * se_m + 1e-5) << filter_name(kind) << " " << r;
  }
}

TEST(Filter, OffsetsAreDistributedLikeTheFilter) {
  // Chi-square of dx over 16 equal bins of [-r, r] against the integral of |f1| over each bin,
  // from sample 0 of 128 x 128 pixels (independent uniform points).
  const Filter f(FilterKind::gaussian, 1.5);
  std::vector<int> counts(16, 0);
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) {
      const FilterSample s = f.sample(sampling::PixelSampler(x, y).get_2d(0, 0));
      ++counts[static_cast<std::size_t>(std::min(15, int((s.dx + 1.5f) / 3.0f * 16)))];
    }
  const double total = integrate(f, [](double) { return 1.0; });
  double chi2 = 0;
  for (int b = 0; b < 16; ++b) {
    const double lo = -1.5 + 3.0 * b / 16, hi = lo + 3.0 / 16;
    const double p = integrate(f, [&](double x) { return x >= lo && x < hi ? 1.0 : 0.0; }) / total;
    const double e = p * 128 * 128;
    chi2 +=
        (counts[static_cast<std::size_t>(b)] - e) * (counts[static_cast<std::size_t>(b)] - e) / e;
  }
  EXPECT_LT(chi2, test::chi_square_critical_1e6(15));
}

}  // namespace
}  // namespace thaw::render
