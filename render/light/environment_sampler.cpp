#include "render/light/environment_sampler.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace thaw::render {

namespace {

constexpr double kPi = std::numbers::pi;

Vec3 direction_of(double theta, double phi) {
  const double s = std::sin(theta);
  return Vec3{float(s * std::cos(phi)), float(std::cos(theta)), float(s * std::sin(phi))};
}

/// The index of the last cdf entry <= x in [begin, end) (cdf[begin] = 0, increasing).
std::size_t find_interval(const std::vector<double>& cdf, std::size_t begin, std::size_t count,
                          double x) {
  const auto first = cdf.begin() + static_cast<std::ptrdiff_t>(begin);
  const auto it = std::upper_bound(first, first + static_cast<std::ptrdiff_t>(count) + 1, x);
  const std::ptrdiff_t i = (it - first) - 1;
  return static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(i, 0, std::ptrdiff_t(count) - 1));
}

}  // namespace

EnvironmentSampler::EnvironmentSampler(const Environment& env, int width, int height)
    : m_width(width), m_height(height) {
  const auto w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height);
  std::vector<double> weight(w * h);
  double total = 0.0;
  for (std::size_t j = 0; j < h; ++j) {
    // The cell's solid angle: dphi (cos(theta0) - cos(theta1)).
    const double t0 = kPi * double(j) / double(h), t1 = kPi * double(j + 1) / double(h);
    const double solid = 2.0 * kPi / double(w) * (std::cos(t0) - std::cos(t1));
    for (std::size_t i = 0; i < w; ++i) {
      double lum = 0.0;
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
          const double theta = kPi * (double(j) + 0.25 + 0.5 * a) / double(h);
          const double phi = 2.0 * kPi * (double(i) + 0.25 + 0.5 * b) / double(w);
          const Rgb c = env.radiance(direction_of(theta, phi));
          lum += 0.25 * (0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b);  // Rec. 709 luminance
        }
      weight[j * w + i] = lum * solid;
      total += lum * solid;
    }
  }
  if (!(total > 0.0) || !std::isfinite(total)) return;
  m_empty = false;
  // A floor: every cell keeps a density (directions the table missed are still drawn).
  const double floor = 1e-3 * total / double(w * h);
  total = 0.0;
  for (double& x : weight) {
    x += floor;
    total += x;
  }
  m_cell_probability.resize(w * h);
  m_row_cdf.assign(h + 1, 0.0);
  m_cell_cdf.assign(h * (w + 1), 0.0);
  for (std::size_t j = 0; j < h; ++j) {
    double row = 0.0;
    for (std::size_t i = 0; i < w; ++i) {
      m_cell_probability[j * w + i] = float(weight[j * w + i] / total);
      row += weight[j * w + i];
      m_cell_cdf[j * (w + 1) + i + 1] = row;
    }
    for (std::size_t i = 1; i <= w; ++i) m_cell_cdf[j * (w + 1) + i] /= row;
    m_row_cdf[j + 1] = m_row_cdf[j] + row / total;
  }
  m_row_cdf[h] = 1.0;
}

Vec3 EnvironmentSampler::sample(sampling::Point2 u, float& pdf) const {
  const auto w = static_cast<std::size_t>(m_width), h = static_cast<std::size_t>(m_height);
  const std::size_t j = find_interval(m_row_cdf, 0, h, u.x);
  const double row_p = m_row_cdf[j + 1] - m_row_cdf[j];
  const double du = row_p > 0.0 ? std::clamp((u.x - m_row_cdf[j]) / row_p, 0.0, 1.0) : 0.5;
  const std::size_t base = j * (w + 1);
  const std::size_t i = find_interval(m_cell_cdf, base, w, u.y);
  const double cell_p = m_cell_cdf[base + i + 1] - m_cell_cdf[base + i];
  const double dv =
      cell_p > 0.0 ? std::clamp((u.y - m_cell_cdf[base + i]) / cell_p, 0.0, 1.0) : 0.5;
  // Uniform in solid angle inside the cell: cos(theta) linear in du.
  const double t0 = kPi * double(j) / double(h), t1 = kPi * double(j + 1) / double(h);
  const double cos_theta = std::cos(t0) + (std::cos(t1) - std::cos(t0)) * du;
  const double theta = std::acos(std::clamp(cos_theta, -1.0, 1.0));
  const double phi = 2.0 * kPi * (double(i) + dv) / double(w);
  const double solid = 2.0 * kPi / double(w) * (std::cos(t0) - std::cos(t1));
  pdf = float(double(m_cell_probability[j * w + i]) / solid);
  return direction_of(theta, phi);
}

float EnvironmentSampler::pdf(const Vec3& d) const {
  const auto w = static_cast<std::size_t>(m_width), h = static_cast<std::size_t>(m_height);
  const double theta = std::acos(std::clamp(double(d.y), -1.0, 1.0));
  double phi = std::atan2(double(d.z), double(d.x));
  if (phi < 0.0) phi += 2.0 * kPi;
  const auto j = std::min(h - 1, static_cast<std::size_t>(theta / kPi * double(h)));
  const auto i = std::min(w - 1, static_cast<std::size_t>(phi / (2.0 * kPi) * double(w)));
  const double t0 = kPi * double(j) / double(h), t1 = kPi * double(j + 1) / double(h);
  const double solid = 2.0 * kPi / double(w) * (std::cos(t0) - std::cos(t1));
  return float(double(m_cell_probability[j * w + i]) / solid);
}

}  // namespace thaw::render
