#pragma once
// Surface colour as a function of position: solid, or a 3D checker (colour 0 where
// floor((x-ox)/s) + floor((y-oy)/s) + floor((z-oz)/s) is even, as in POV-Ray's `checker`).
// eval_filtered() is the checker's exact mean over an axis-aligned box, in closed form: the
// checker is (1 + q)/2 colour 0 + (1 - q)/2 colour 1 with q = s(x) s(y) s(z), s(t) = (-1)^floor(t)
// a square wave; over a box the mean of the product is the product of the per-axis means, and a
// square wave's box mean is a difference of its integral, a triangle wave (the box-filtered
// checkerboard of Apodaca & Gritz 2000, "Advanced RenderMan", sec. 11.4; Quilez, "Filtering
// checkerboards", iquilezles.org/articles/checkerfiltering). eval_footprint() averages it over the
// box bounding a ray's footprint, an ellipse on the surface (TextureFootprint), in the texture's
// axes or along the plane's diagonals, whichever is tighter (diagonal_box_mean: also closed form).
// Far away, where the footprint spans many cells, both tend to the cells' mean colour: no moire at
// the horizon. Procedural noise (render/material/noise.h: Perlin fBm, Worley cells, wood planks,
// slate) blends colour 0 into colour 1 by a value in [0, 1] filtered to the footprint's width,
// and may carry a bump height (bump_m times the same value) for the shading normal.
// Knows nothing about rays, cameras or pixels.
#include <algorithm>
#include <cmath>
#include <string>

#include "render/material/noise.h"
#include "render/math/color.h"
#include "render/math/vec3.h"

namespace thaw::render {

/// The part of a surface one texture lookup stands for: an ellipse centred at `center` with
/// half-axes `major` along the unit vector `major_axis` and `minor` along the unit vector
/// `minor_axis` (both in the surface's plane, orthogonal) [scene units].
struct TextureFootprint {
  Vec3 center, major_axis, minor_axis;
  float major = 0, minor = 0;
};

struct Texture {
  enum class Kind { solid, checker, noise };
  enum class Pattern { perlin, worley, wood, slate };
  Kind kind = Kind::solid;
  /// noise: the pattern, its octaves (perlin, slate), and the bump height [m] of value 1
  Pattern pattern = Pattern::perlin;
  int octaves = 5;
  float bump_m = 0.0f;
  Rgb color0{0.8f, 0.8f, 0.8f};
  Rgb color1{0.0f, 0.0f, 0.0f};
  /// checker cell size; noise feature size (wood: plank width) [scene units]
  float size = 1.0f;
  /// checker and noise origin [scene units]
  Vec3 offset{0, 0, 0};

  /// The noise value in [0, 1] at p for a footprint of width w [scene units].
  float noise_value(const Vec3& p, float w) const {
    const float inv = 1.0f / size;
    const Vec3 q = (p - offset) * inv;
    const float wq = w * inv;
    switch (pattern) {
      case Pattern::perlin:
        return std::clamp(0.5f + 0.6f * noise::fbm(q, wq, octaves), 0.0f, 1.0f);
      case Pattern::worley:
        return std::clamp(noise::worley(q, wq), 0.0f, 1.0f);
      case Pattern::wood:
        return noise::wood(q, wq);
      case Pattern::slate:
        return noise::slate(q, wq);
    }
    return 0.0f;
  }

  Rgb eval(const Vec3& p) const {
    if (kind == Kind::solid) return color0;
    if (kind == Kind::noise) {
      const float v = noise_value(p, 0.0f);
      return color0 * (1.0f - v) + color1 * v;
    }
    const float inv = 1.0f / size;
    const long long ix = floor_to_integer((p.x - offset.x) * inv);
    const long long iy = floor_to_integer((p.y - offset.y) * inv);
    const long long iz = floor_to_integer((p.z - offset.z) * inv);
    return ((ix + iy + iz) & 1) == 0 ? color0 : color1;
  }

  /// floor(v) as an integer, for |v| < 2^63 (what the checker's cast of std::floor needed too),
  /// without a libm call: the truncation, one less where it rounded up (negative non-integers).
  /// Exact: a truncated float is an integer float represents, so the comparison is exact.
  static long long floor_to_integer(float v) {
    const auto i = static_cast<long long>(v);
    return static_cast<float>(i) > v ? i - 1 : i;
  }
  /// The same for a double, as a double, for |v| < 2^62 (the triangle wave's argument).
  static double floor_to_integer(double v) {
    const auto i = static_cast<double>(static_cast<long long>(v));
    return i > v ? i - 1.0 : i;
  }

  /// The mean colour over a footprint centred at p whose half-extent along each axis is
  /// `half_extent` [scene units] (a box filter per axis); eval(p) where the extent is 0.
  Rgb eval_filtered(const Vec3& p, const Vec3& half_extent) const {
    if (kind == Kind::solid) return color0;
    if (kind == Kind::noise) {
      const float v =
          noise_value(p, 2.0f * std::max({half_extent.x, half_extent.y, half_extent.z}));
      return color0 * (1.0f - v) + color1 * v;
    }
    const double q = checker_mean(p, half_extent);
    const auto w0 = static_cast<float>(0.5 * (1.0 + q)), w1 = static_cast<float>(0.5 * (1.0 - q));
    return color0 * w0 + color1 * w1;
  }

  /// Mean of s(t) = (-1)^floor(t) over [t - h, t + h] [cells]: (S(t + h) - S(t - h)) / 2h with
  /// S the triangle wave S(t) = 1 - |(t mod 2) - 1|; s(t) itself for h below float resolution.
  /// 0 beyond |t| + h = 2^52 (no cell is resolved there: the mean is at most 1/2h, or no double
  /// lies inside a cell). No libm call (floor_to_integer).
  static double square_wave_mean(double t, double h) {
    if (!(std::abs(t) + h < 0x1p52)) return 0.0;
    auto triangle = [](double u) {
      return 1.0 - std::abs(u - 2.0 * floor_to_integer(0.5 * u) - 1.0);
    };
    if (!(h > 1e-7 * std::max(1.0, std::abs(t))))
      return (static_cast<long long>(floor_to_integer(t)) & 1) == 0 ? 1.0 : -1.0;
    return (triangle(t + h) - triangle(t - h)) / (2.0 * h);
  }

  /// The mean colour over footprint `f` (an ellipse on the surface with half-axes A = major,
  /// B = minor) as the exact mean over the box bounding it in one of two frames of the surface's
  /// plane: the texture's own axes (the box per axis i half sqrt((A a_i)^2 + (B b_i)^2): Quilez's
  /// box of the texture-space derivatives), or the plane's two diagonals (diagonal_box_mean),
  /// where the checker is as simple: along a diagonal its cells of one colour touch corner to
  /// corner. The tighter box is taken (the smaller area), both blended in between (diagonal share
  /// ramping from 0 where the two areas are equal to 1 where the diagonal box is 0.7 of the
  /// other: no seam on the floor where the view turns). A footprint along a texture axis or a
  /// diagonal is then bounded by a box of its own size; a long one between them (22.5 degrees from
  /// both) by one up to 0.38 A across, as before: the checker's converging rows survive where they
  /// exist, seen along an axis or along a diagonal, and fade to the mean colour where the view
  /// compresses them below the footprint (one box of the texture's axes around a floor seen at 45
  /// degrees to its rows, 0.7 A across instead of B, turned it flat far too soon). The axis normal
  /// to the plane (the largest component of a x b) enters as its own per-axis box factor.
  /// eval(center) where the footprint has no extent.
  Rgb eval_footprint(const TextureFootprint& f) const {
    if (kind == Kind::solid) return color0;
    if (kind == Kind::noise) {
      // Isotropic filtering: the footprint's width taken as its minor diameter, or half its
      // major one where longer (a grazing view keeps some detail along the view and blurs it
      // less than the full ellipse would; the haze fades the far floor anyway).
      const float v = noise_value(f.center, 2.0f * std::max(f.minor, 0.5f * f.major));
      return color0 * (1.0f - v) + color1 * v;
    }
    const Vec3 a = f.major_axis * f.major, b = f.minor_axis * f.minor;
    // Squared half-extents of the boxes bounding the ellipse (square roots only where used).
    const auto sq = [](float u, float v) { return u * u + v * v; };
    const Vec3 axis_sq{sq(a.x, b.x), sq(a.y, b.y), sq(a.z, b.z)};
    // The plane's two texture axes i, j (k: the one closest to the normal).
    const Vec3 n = cross(f.major_axis, f.minor_axis);
    const int k = std::abs(n.x) >= std::abs(n.y) && std::abs(n.x) >= std::abs(n.z) ? 0
                  : std::abs(n.y) >= std::abs(n.z)                                 ? 1
                                                                                   : 2;
    const int i = k == 0 ? 1 : 0, j = k == 2 ? 1 : 2;
    // Half-extents along p = t_i + t_j and m = t_i - t_j (t in cells); the diagonal box's area
    // in the plane is 2 h_p h_m (the map (t_i, t_j) -> (p, m) doubles areas), the axis box's
    // 4 h_i h_j: their ratio rho = h_p h_m / (2 h_i h_j). The diagonal box's share w ramps from
    // 0 at rho = 1 (equal areas: a round footprint, or a long one 22.5 degrees from both frames)
    // to 1 at rho = 0.7 (27.5 degrees for a long one).
    const float hp_sq = sq(a[i] + a[j], b[i] + b[j]), hm_sq = sq(a[i] - a[j], b[i] - b[j]);
    const float axis_area_sq = 4.0f * axis_sq[i] * axis_sq[j];
    // A footprint shorter than half a cell straddles at most one cell edge in either frame: the
    // two boxes differ only in how they soften it, so the axis box serves (the diagonal one's
    // share ramps in from 0.5 to 1 cell of major half-axis: the near floor skips it).
    const float length_cells = f.major / size;
    const float w =
        axis_area_sq > 0.0f && length_cells > 0.5f
            ? std::clamp((1.0f - std::sqrt(hp_sq * hm_sq / axis_area_sq)) / 0.3f, 0.0f, 1.0f) *
                  std::min(2.0f * length_cells - 1.0f, 1.0f)
            : 0.0f;
    const float half_k = std::sqrt(axis_sq[k]);
    double q = 0.0;
    if (w < 1.0f) {
      Vec3 axis_half;
      axis_half[i] = std::sqrt(axis_sq[i]), axis_half[j] = std::sqrt(axis_sq[j]);
      axis_half[k] = half_k;
      q += (1.0 - w) * checker_mean(f.center, axis_half);
    }
    if (w > 0.0f) {
      const double inv = 1.0 / double(size);
      const double ti = double(f.center[i] - offset[i]) * inv,
                   tj = double(f.center[j] - offset[j]) * inv;
      q += w * square_wave_mean(double(f.center[k] - offset[k]) * inv, double(half_k) * inv) *
           diagonal_box_mean(ti + tj, ti - tj, double(std::sqrt(hp_sq)) * inv,
                             double(std::sqrt(hm_sq)) * inv);
    }
    const auto w0 = static_cast<float>(0.5 * (1.0 + q)), w1 = static_cast<float>(0.5 * (1.0 - q));
    return color0 * w0 + color1 * w1;
  }

  /// The checker's sign q = s(x) s(y) s(z) (+1 on colour 0) averaged over the box p +- half
  /// [scene units]: eval_filtered's weight.
  double checker_mean(const Vec3& p, const Vec3& half_extent) const {
    const double inv = 1.0 / double(size);
    return square_wave_mean(double(p.x - offset.x) * inv, double(half_extent.x) * inv) *
           square_wave_mean(double(p.y - offset.y) * inv, double(half_extent.y) * inv) *
           square_wave_mean(double(p.z - offset.z) * inv, double(half_extent.z) * inv);
  }

  /// The mean of s(u) s(v) (a 2D checker of unit cells, +1 where floor u + floor v is even) over
  /// the box p +- hp, m +- hm in its diagonal coordinates p = u + v, m = u - v [cells]. Closed
  /// form: sin(pi u) sin(pi v) = (cos(pi m) - cos(pi p)) / 2, so s(u) s(v) = sign(T(p) - T(m))
  /// with T the distance to the nearest even integer (the triangle wave of square_wave_mean),
  /// periodic in p and in m apart; its integral from 0 is diagonal_integral. Extents are taken
  /// as at least 1e-4 cells (the corners' differences keep 1e-8 of their precision; the
  /// diagonal frame serves elongated footprints only).
  static double diagonal_box_mean(double p, double m, double hp, double hm) {
    if (!(std::abs(p) + hp < 0x1p52) || !(std::abs(m) + hm < 0x1p52)) return 0.0;
    hp = std::max(hp, 1e-4), hm = std::max(hm, 1e-4);
    // Both integrands are 2-periodic: centre p and m in [0, 2) so the corners stay small.
    p -= 2.0 * floor_to_integer(0.5 * p), m -= 2.0 * floor_to_integer(0.5 * m);
    const Levels p1 = signed_levels(p + hp), p0 = signed_levels(p - hp), m1 = signed_levels(m + hm),
                 m0 = signed_levels(m - hm);
    const double sum = diagonal_integral(p1, m1) - diagonal_integral(p0, m1) -
                       diagonal_integral(p1, m0) + diagonal_integral(p0, m0);
    return sum / (4.0 * hp * hm);
  }

  /// How often [0, |P|] meets each level t of T: C + sigma [t < alpha]. Each full period of 2
  /// meets every level twice; a remainder r <= 1 meets [0, r) once more; r > 1 meets [0, 1] once
  /// and (2 - r, 1] once more, i.e. 2 - [t < 2 - r]. `sign`: P's (the integral from 0 is odd).
  struct Levels {
    double c, sigma, alpha, sign;
  };
  static Levels signed_levels(double P) {
    const double a = std::abs(P), periods = floor_to_integer(0.5 * a), r = a - 2.0 * periods;
    const double sign = P < 0.0 ? -1.0 : 1.0;
    return r <= 1.0 ? Levels{2.0 * periods, 1.0, r, sign}
                    : Levels{2.0 * periods + 2.0, -1.0, 2.0 - r, sign};
  }

  /// F(P, M) = integral over [0, P] x [0, M] of sign(T(p) - T(m)) dm dp, from the levels of P
  /// and M (T is even, so F is odd in each). On [0, |P|] the levels T(p) in [0, 1] are met with
  /// weight w_P(t) = C + sigma [t < alpha], so F = integral over t, tau in [0, 1]^2 of
  /// sign(t - tau) w_P(t) w_M(tau): with J(x, y) = integral over [0, x] x [0, y] of
  /// sign(t - tau) = (x - y) min(x, y), and J(1, 1) = 0,
  /// F = C_P s_M J(1, a_M) + s_P C_M J(a_P, 1) + s_P s_M J(a_P, a_M).
  static double diagonal_integral(const Levels& a, const Levels& b) {
    const auto J = [](double x, double y) { return (x - y) * std::min(x, y); };
    return a.sign * b.sign *
           (a.c * b.sigma * J(1.0, b.alpha) + a.sigma * b.c * J(a.alpha, 1.0) +
            a.sigma * b.sigma * J(a.alpha, b.alpha));
  }
  static double diagonal_integral(double P, double M) {
    return diagonal_integral(signed_levels(P), signed_levels(M));
  }
};

/// The noise pattern named `name` ("perlin", "worley", "wood", "slate"); false for any other.
inline bool noise_pattern_from_name(const std::string& name, Texture::Pattern& pattern) {
  if (name == "perlin")
    pattern = Texture::Pattern::perlin;
  else if (name == "worley")
    pattern = Texture::Pattern::worley;
  else if (name == "wood")
    pattern = Texture::Pattern::wood;
  else if (name == "slate")
    pattern = Texture::Pattern::slate;
  else
    return false;
  return true;
}

}  // namespace thaw::render
