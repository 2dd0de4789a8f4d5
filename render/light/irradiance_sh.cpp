// Irradiance from nine spherical-harmonic coefficients; see irradiance_sh.h.
#include "render/light/irradiance_sh.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace thaw::render {
namespace {

/// The real spherical harmonics Y_lm up to l = 2 at unit direction d (RH01, eq. 3).
std::array<double, 9> basis(double x, double y, double z) {
  return {0.282095,
          0.488603 * y,
          0.488603 * z,
          0.488603 * x,
          1.092548 * x * y,
          1.092548 * y * z,
          0.315392 * (3.0 * z * z - 1.0),
          1.092548 * x * z,
          0.546274 * (x * x - y * y)};
}

/// A_l of the clamped cosine, per coefficient (RH01, eq. 8).
constexpr std::array<double, 9> kCosineLobe = {
    std::numbers::pi,           2.0 * std::numbers::pi / 3, 2.0 * std::numbers::pi / 3,
    2.0 * std::numbers::pi / 3, std::numbers::pi / 4,       std::numbers::pi / 4,
    std::numbers::pi / 4,       std::numbers::pi / 4,       std::numbers::pi / 4};

}  // namespace

namespace {

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton's iteration on P_n; Press et al.,
/// Numerical Recipes, gauleg): exact for polynomials of degree < 2n.
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), dp = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = 0.0;
      for (int k = 1; k <= n; ++k) {
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p2) / k;
      }
      dp = n * (z * p0 - p1) / (z * z - 1.0);
      const double step = p0 / dp;
      z -= step;
      if (std::abs(step) < 1e-15) break;
    }
    x[i] = -z;
    x[n - 1 - i] = z;
    w[i] = w[n - 1 - i] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
}

}  // namespace

IrradianceSH IrradianceSH::project(const std::function<Rgb(const Vec3&)>& radiance, int rows) {
  // dw = dz dphi: Gauss-Legendre in z = cos(theta) and the midpoint rule in phi integrate the
  // l <= 2 harmonics times a constant exactly (polynomials of degree 2 in z, trigonometric
  // polynomials of degree 2 in phi), so a constant radiance projects to L_00 alone, to rounding.
  const int cols = 2 * rows;
  std::vector<double> zs, ws;
  gauss_legendre(rows, zs, ws);
  const double dphi = 2.0 * std::numbers::pi / cols;
  std::array<std::array<double, 3>, 9> sum{};
  for (int j = 0; j < rows; ++j) {
    const double z = zs[j], st = std::sqrt(std::max(0.0, 1.0 - z * z));
    for (int i = 0; i < cols; ++i) {
      const double phi = (i + 0.5) * dphi;
      const double x = st * std::cos(phi), y = z, zz = st * std::sin(phi);
      const double w = ws[j] * dphi;
      const Rgb l = radiance(Vec3{float(x), float(y), float(zz)});
      const std::array<double, 9> y_lm = basis(x, y, zz);
      for (int k = 0; k < 9; ++k) {
        sum[k][0] += w * y_lm[k] * l.r;
        sum[k][1] += w * y_lm[k] * l.g;
        sum[k][2] += w * y_lm[k] * l.b;
      }
    }
  }
  IrradianceSH sh;
  for (int k = 0; k < 9; ++k) sh.m_c[k] = Rgb{float(sum[k][0]), float(sum[k][1]), float(sum[k][2])};
  return sh;
}

Rgb IrradianceSH::irradiance(const Vec3& n) const {
  const std::array<double, 9> y_lm = basis(n.x, n.y, n.z);
  double r = 0.0, g = 0.0, b = 0.0;
  for (int k = 0; k < 9; ++k) {
    const double a = kCosineLobe[k] * y_lm[k];
    r += a * m_c[k].r;
    g += a * m_c[k].g;
    b += a * m_c[k].b;
  }
  return Rgb{float(std::max(r, 0.0)), float(std::max(g, 0.0)), float(std::max(b, 0.0))};
}

}  // namespace thaw::render
