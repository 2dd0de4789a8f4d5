#pragma once
// Surface colour as a function of position: solid, or a 3D checker (colour 0 where
// floor((x-ox)/s) + floor((y-oy)/s) + floor((z-oz)/s) is even, as in POV-Ray's `checker`).
// eval_filtered() averages the checker over a ray's footprint (an ellipse on the surface, boxed
// per axis) in closed form: the checker is (1 + q)/2 colour 0 + (1 - q)/2 colour 1 with
// q = s(x) s(y) s(z), s(t) = (-1)^floor(t) a square wave, and a square wave's box average is a
// difference of its integral, a triangle wave (the closed-form box-filtered checkerboard of
// Apodaca & Gritz 2000, "Advanced RenderMan", sec. 11.4; pbrt-v3 Checkerboard2DTexture "closed
// form"). Far away, where the footprint spans many cells, it tends to the cells' mean colour: no
// moire at the horizon. Knows nothing about rays.
#include <algorithm>
#include <cmath>

#include "render/math/color.h"
#include "render/math/vec3.h"

namespace thaw::render {

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
  static double square_wave_mean(double t, double h) {
    auto triangle = [](double u) { return 1.0 - std::abs(u - 2.0 * std::floor(u / 2.0) - 1.0); };
    if (!(h > 1e-7 * std::max(1.0, std::abs(t))))
      return (static_cast<long long>(std::floor(t)) & 1) == 0 ? 1.0 : -1.0;
    return (triangle(t + h) - triangle(t - h)) / (2.0 * h);
  }
};

}  // namespace thaw::render
