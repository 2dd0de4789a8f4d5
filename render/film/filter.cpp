#include "render/film/filter.h"

#include <algorithm>
#include <cmath>

#include "base/check.h"

namespace thaw::render {

namespace {

/// Bins of the tabulated 1D filter: f1 varies by < 1 % within a bin for every radius allowed, so
/// the weights f / pdf stay within 1 % of each other (low variance); the estimate is unbiased
/// whatever the bin count, since the weights use the pdf actually sampled.
constexpr int kBins = 256;

double mitchell_1d(double x) {
  // Mitchell & Netravali 1988, eq. 8, on |x| in [0, 2], with B = C = 1/3.
  constexpr double B = 1.0 / 3.0, C = 1.0 / 3.0;
  x = std::abs(x);
  if (x < 1.0)
    return ((12 - 9 * B - 6 * C) * x * x * x + (-18 + 12 * B + 6 * C) * x * x + (6 - 2 * B)) / 6.0;
  if (x < 2.0)
    return ((-B - 6 * C) * x * x * x + (6 * B + 30 * C) * x * x + (-12 * B - 48 * C) * x +
            (8 * B + 24 * C)) /
           6.0;
  return 0.0;
}

}  // namespace

std::optional<FilterKind> filter_kind_from_name(std::string_view name) {
  if (name == "box") return FilterKind::box;
  if (name == "gaussian") return FilterKind::gaussian;
  if (name == "mitchell") return FilterKind::mitchell;
  return std::nullopt;
}

const char* filter_name(FilterKind kind) {
  switch (kind) {
    case FilterKind::box:
      return "box";
    case FilterKind::gaussian:
      return "gaussian";
    case FilterKind::mitchell:
      return "mitchell";
  }
  return "?";
}

double default_filter_radius(FilterKind kind) {
  switch (kind) {
    case FilterKind::box:
      return 0.5;
    case FilterKind::gaussian:
      return 1.5;
    case FilterKind::mitchell:
      return 2.0;
  }
  return 0.5;
}

Filter::Filter(FilterKind kind, double radius)
    : m_kind(kind), m_radius(static_cast<float>(radius)) {
  // The Gaussian's value at the radius, subtracted from every evaluation (one exp per sample
  // instead of two): the same double as evaluate_1d computed before, so the same weights.
  {
    const double r = m_radius, s = r / 3.0;
    m_gaussian_floor = std::exp(-r * r / (2 * s * s));
  }
  if (kind == FilterKind::gaussian) {
    // f1 at kGaussianNodes + 1 evenly spaced |x| in [0, r] (and the last once more): a sample's
    // weight reads it instead of calling exp twice (1.2 % of a default-film frame).
    m_gaussian_table.resize(kGaussianNodes + 2);
    for (int i = 0; i <= kGaussianNodes; ++i)
      m_gaussian_table[static_cast<std::size_t>(i)] =
          static_cast<float>(gaussian_1d(double(m_radius) * i / kGaussianNodes));
    m_gaussian_table[kGaussianNodes + 1] = m_gaussian_table[kGaussianNodes];
  }
  THAW_CHECK(radius >= kMinFilterRadius && radius <= kMaxFilterRadius,
             "filter radius out of range");
  if (kind == FilterKind::box) return;  // sampled exactly, weight 1
  m_abs.resize(kBins);
  m_cdf.resize(kBins + 1);
  const double width = 2.0 * radius / kBins;
  double abs_sum = 0, signed_sum = 0;
  for (int i = 0; i < kBins; ++i) {
    // The bin's value is f1's mean over the bin (Simpson), a fair stand-in for |f1| there.
    const double x0 = -radius + i * width, x1 = x0 + width;
    const double f = (evaluate_1d(float(x0)) + 4.0 * evaluate_1d(float(0.5 * (x0 + x1))) +
                      evaluate_1d(float(x1))) /
                     6.0;
    m_abs[static_cast<std::size_t>(i)] = static_cast<float>(std::abs(f));
    abs_sum += std::abs(f) * width;
    signed_sum += f * width;
    m_cdf[static_cast<std::size_t>(i + 1)] = static_cast<float>(abs_sum);
  }
  for (float& c : m_cdf) c = static_cast<float>(c / abs_sum);
  m_cdf.back() = 1.0f;
  m_guide.resize(kGuideCells);
  for (int g = 0; g < kGuideCells; ++g)
    m_guide[static_cast<std::size_t>(g)] = static_cast<int>(
        std::upper_bound(m_cdf.begin(), m_cdf.end(), float(g) / float(kGuideCells)) -
        m_cdf.begin());
  m_abs_integral = static_cast<float>(abs_sum);
  // Per bin: 1 / (its CDF step) and 1 / pdf (0 where the pdf is 0), multiplied instead of
  // divided per sample.
  m_inv_bin_mass.resize(kBins);
  m_inv_pdf.resize(kBins);
  for (std::size_t i = 0; i < std::size_t(kBins); ++i) {
    const float mass = m_cdf[i + 1] - m_cdf[i], pdf = m_abs[i] / m_abs_integral;
    m_inv_bin_mass[i] = mass > 0.0f ? 1.0f / mass : 0.0f;
    m_inv_pdf[i] = pdf > 0.0f ? 1.0f / pdf : 0.0f;
  }
  // The signed integral of f1 itself, by Simpson on a fine grid (not of the table), so weights
  // average to 1 for the true filter.
  constexpr int kFine = 4096;
  const double h = 2.0 * radius / kFine;
  double s = evaluate_1d(float(-radius)) + evaluate_1d(float(radius));
  for (int i = 1; i < kFine; ++i) s += (i % 2 ? 4.0 : 2.0) * evaluate_1d(float(-radius + i * h));
  m_signed_integral = static_cast<float>(s * h / 3.0);
}

double Filter::gaussian_1d(double x) const {
  const double s = double(m_radius) / 3.0;
  return std::exp(-x * x / (2 * s * s)) - m_gaussian_floor;
}

float Filter::evaluate_1d(float x) const {
  const double r = m_radius, ax = std::abs(double(x));
  if (ax > r) return 0.0f;
  switch (m_kind) {
    case FilterKind::box:
      return 1.0f;
    case FilterKind::gaussian: {
      // Linear interpolation in the table: error <= h^2 / 8 max|f1''| = (r / N)^2 / 8 * 9 / r^2
      // = 9 / (8 N^2) = 1.1e-6 (f1'' peaks at x = 0: 1 / s^2, s = r / 3).
      const float v = float(ax) * (float(kGaussianNodes) / m_radius);
      const auto i = std::min(static_cast<std::size_t>(v), std::size_t(kGaussianNodes));
      const float lo = m_gaussian_table[i], hi = m_gaussian_table[i + 1];
      return lo + (hi - lo) * (v - float(i));
    }
    case FilterKind::mitchell:
      return static_cast<float>(mitchell_1d(2.0 * ax / r));
  }
  return 0.0f;
}

float Filter::sample_1d(float u, float& ratio) const {
  // Invert the piecewise-linear CDF: the first cdf[i] > u from the guide table's start (u >= g /
  // kGuideCells, so upper_bound(u) is at or after it; cdf[kBins] = 1 > u ends the scan), the
  // bin before it, then uniform inside the bin.
  const int cell = std::clamp(static_cast<int>(u * float(kGuideCells)), 0, kGuideCells - 1);
  int i = m_guide[static_cast<std::size_t>(cell)];
  while (i < kBins && m_cdf[static_cast<std::size_t>(i)] <= u) ++i;
  const int bin = std::clamp(i - 1, 0, kBins - 1);
  const auto b = static_cast<std::size_t>(bin);
  const float frac =
      m_cdf[b + 1] > m_cdf[b] ? std::clamp((u - m_cdf[b]) * m_inv_bin_mass[b], 0.0f, 1.0f) : 0.5f;
  const float width = 2.0f * m_radius / kBins;
  const float x = -m_radius + (float(bin) + frac) * width;
  ratio = evaluate_1d(x) * m_inv_pdf[b];
  return x;
}

FilterSample Filter::sample(sampling::Point2 u) const {
  FilterSample s;
  if (m_kind == FilterKind::box) {
    s.dx = (2.0f * u.x - 1.0f) * m_radius;
    s.dy = (2.0f * u.y - 1.0f) * m_radius;
    return s;
  }
  float rx = 0, ry = 0;
  s.dx = sample_1d(u.x, rx);
  s.dy = sample_1d(u.y, ry);
  s.weight = rx * ry / (m_signed_integral * m_signed_integral);
  return s;
}

}  // namespace thaw::render
