#pragma once
// Surface colour as a function of position: solid, or a 3D checker (colour 0 where
// floor((x-ox)/s) + floor((y-oy)/s) + floor((z-oz)/s) is even, as in POV-Ray's `checker`).
// eval_filtered() is the checker's exact mean over an axis-aligned box, in closed form: the
// checker is (1 + q)/2 colour 0 + (1 - q)/2 colour 1 with q = s(x) s(y) s(z), s(t) = (-1)^floor(t)
// a square wave; over a box the mean of the product is the product of the per-axis means, and a
// square wave's box mean is a difference of its integral, a triangle wave (the box-filtered
// checkerboard of Apodaca & Gritz 2000, "Advanced RenderMan", sec. 11.4; Quilez, "Filtering
// checkerboards", iquilezles.org/articles/checkerfiltering). eval_footprint() averages it over the
// box bounding a ray's footprint, an ellipse on the surface (TextureFootprint). Far away, where the
// footprint spans many cells, both tend to the cells' mean colour: no moire at the horizon. Knows
// nothing about rays, cameras or pixels.
#include <algorithm>
#include <cmath>

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
  enum class Kind { solid, checker };
  Kind kind = Kind::solid;
  Rgb color0{0.8f, 0.8f, 0.8f};
  Rgb color1{0.0f, 0.0f, 0.0f};
  /// checker cell size [scene units]
  float size = 1.0f;
  /// checker origin [scene units]
  Vec3 offset{0, 0, 0};

  Rgb eval(const Vec3& p) const {
    if (kind == Kind::solid) return color0;
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
    const double inv = 1.0 / double(size);
    const double q = square_wave_mean(double(p.x - offset.x) * inv, double(half_extent.x) * inv) *
                     square_wave_mean(double(p.y - offset.y) * inv, double(half_extent.y) * inv) *
                     square_wave_mean(double(p.z - offset.z) * inv, double(half_extent.z) * inv);
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

  /// The mean colour over footprint `f` (an ellipse on the surface) as the mean over the
  /// axis-aligned box bounding it: half-extent per axis i sqrt((A a_i)^2 + (B b_i)^2) for
  /// half-axes A, B along unit a, b (Quilez's box of the texture-space derivatives). One
  /// closed-form lookup. Exact in kind where the ellipse's long axis follows a texture axis; seen
  /// diagonally the box is as wide across the view as along it, so checks resolved across the
  /// view but compressed below the footprint along it fade with those along it (a grazing floor
  /// at 45 degrees to its rows turns flat where one along a row keeps its converging stripes).
  /// Boxes along the long axis would keep them but leave a residual that varies from sample to
  /// sample (speckle where the few samples of a pixel cannot average it; docs/benchmarks.md
  /// "Checker footprint"). eval(center) where the footprint has no extent.
  Rgb eval_footprint(const TextureFootprint& f) const {
    if (kind == Kind::solid) return color0;
    const Vec3 a = f.major_axis * f.major, b = f.minor_axis * f.minor;
    const auto half = [](float u, float v) { return std::sqrt(u * u + v * v); };
    return eval_filtered(f.center, Vec3{half(a.x, b.x), half(a.y, b.y), half(a.z, b.z)});
  }
};

}  // namespace thaw::render
