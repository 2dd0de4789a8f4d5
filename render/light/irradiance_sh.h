#pragma once
// The irradiance an environment gives a surface of any orientation, from the nine order-2
// spherical-harmonic coefficients of its radiance (Ramamoorthi & Hanrahan 2001, "An efficient
// representation for irradiance environment maps", eqs. 7-13): E(n) = sum_lm A_l L_lm Y_lm(n),
// A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4. Smooth and noise-free; exact for a constant radiance
// (E = pi L) and for any radiance that is a polynomial of degree <= 2 in the direction; otherwise
// off by at most (L_max - L_min) * the integral of |max(cos, 0) - its order-2 projection| over
// the sphere (the constant part is exact), about 0.095 (L_max - L_min) in these units.
// Knows nothing about scenes or occlusion: the unoccluded irradiance only.
#include <array>
#include <functional>

#include "render/math/color.h"
#include "render/math/vec3.h"

namespace thaw::render {

class IrradianceSH {
 public:
  /// Projects `radiance(direction)` (unit directions) by quadrature on `rows` Gauss-Legendre
  /// nodes in cos(theta) times 2 rows midpoints in phi (a constant is projected exactly).
  static IrradianceSH project(const std::function<Rgb(const Vec3&)>& radiance, int rows = 64);

  /// Irradiance on a surface with unit normal n: integral of L(w) max(0, n.w) dw, clamped at 0
  /// (the truncated series can ring below zero facing a dark region).
  Rgb irradiance(const Vec3& n) const;

  /// The nine coefficients L_lm (l = 0; l = 1: m = -1, 0, 1; l = 2: m = -2 .. 2).
  const std::array<Rgb, 9>& coefficients() const { return m_c; }

 private:
  std::array<Rgb, 9> m_c{};
};

}  // namespace thaw::render
