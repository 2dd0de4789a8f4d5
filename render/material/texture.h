#pragma once
// Surface colour as a function of position: solid, or a 3D checker (colour 0 where
// floor((x-ox)/s) + floor((y-oy)/s) + floor((z-oz)/s) is even, as in POV-Ray's `checker`).
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
    const auto ix = static_cast<long long>(std::floor((p.x - offset.x) * inv));
    const auto iy = static_cast<long long>(std::floor((p.y - offset.y) * inv));
    const auto iz = static_cast<long long>(std::floor((p.z - offset.z) * inv));
    return ((ix + iy + iz) & 1) == 0 ? color0 : color1;
  }
};

}  // namespace thaw::render
