#pragma once
// Small standalone refraction helpers for checking dispersion against textbook optics: Snell's
// law in vector form (the form an integrator uses) and a thin 2D prism tracer. The renderer's
// own refraction lives with its integrator; these exist so tests can compare a traced prism
// with the minimum-deviation formula n = sin((A + D_min)/2) / sin(A/2) (Born & Wolf sec. 4.7.2)
// for n(lambda) from any IorModel.
#include <cmath>
#include <optional>

namespace thaw::render::optics {

struct Vec2 {
  double x = 0, y = 0;
};
inline Vec2 operator+(Vec2 a, Vec2 b) {
  return {a.x + b.x, a.y + b.y};
}
inline Vec2 operator*(double s, Vec2 a) {
  return {s * a.x, s * a.y};
}
inline double dot(Vec2 a, Vec2 b) {
  return a.x * b.x + a.y * b.y;
}

/// Refracts unit direction `d` at a surface with unit normal `n` facing against d
/// (dot(d, n) < 0), going from index n1 into n2. Empty on total internal reflection.
/// t = eta d + (eta cos_i - cos_t) n, eta = n1 / n2 (pbrt-v4 Refract).
inline std::optional<Vec2> refract(Vec2 d, Vec2 n, double n1, double n2) {
  const double eta = n1 / n2;
  const double cos_i = -dot(d, n);
  const double sin2_t = eta * eta * (1 - cos_i * cos_i);
  if (sin2_t > 1) return std::nullopt;
  const double cos_t = std::sqrt(1 - sin2_t);
  return eta * d + (eta * cos_i - cos_t) * n;
}

/// Deviation [rad] of a ray crossing a prism of apex angle `apex_rad` and index `n` (in a
/// medium of index 1), entering at incidence angle `incidence_rad` on the first face; empty if
/// the ray is totally reflected at the second face. Traced with refract() on both faces.
inline std::optional<double> prism_deviation_rad(double n, double apex_rad, double incidence_rad) {
  // Apex up: each face leans apex/2 from the vertical; outward normals point up-left, up-right.
  const double h = apex_rad / 2;
  const Vec2 n1{-std::cos(h), std::sin(h)};
  const Vec2 n2{std::cos(h), std::sin(h)};
  // Incoming direction making `incidence_rad` with -n1.
  const double a = std::atan2(-n1.y, -n1.x) + incidence_rad;
  const Vec2 d0{std::cos(a), std::sin(a)};
  const auto d1 = refract(d0, n1, 1.0, n);
  if (!d1) return std::nullopt;
  // Leaving through the second face: its inward-facing normal for the ray is -n2.
  const auto d2 = refract(*d1, Vec2{-n2.x, -n2.y}, n, 1.0);
  if (!d2) return std::nullopt;
  return std::acos(std::fmin(1.0, std::fmax(-1.0, dot(d0, *d2))));
}

/// Minimum deviation [rad] from the closed form D = 2 asin(n sin(A/2)) - A.
inline double prism_minimum_deviation_rad(double n, double apex_rad) {
  return 2 * std::asin(n * std::sin(apex_rad / 2)) - apex_rad;
}

}  // namespace thaw::render::optics
