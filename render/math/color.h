#pragma once
// Linear RGB radiance / reflectance. Kept as its own small type so that spectral transport
// (issue 5: a SampledSpectrum of a few wavelengths) can replace it in the integrator without
// touching geometry. Knows nothing about images or scenes.
#include <algorithm>

namespace thaw::render {

struct Rgb {
  float r = 0, g = 0, b = 0;

  constexpr Rgb() = default;
  constexpr Rgb(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
  static constexpr Rgb gray(float v) { return {v, v, v}; }

  constexpr Rgb& operator+=(const Rgb& o) {
    r += o.r;
    g += o.g;
    b += o.b;
    return *this;
  }
  constexpr Rgb& operator*=(const Rgb& o) {
    r *= o.r;
    g *= o.g;
    b *= o.b;
    return *this;
  }
  constexpr Rgb& operator*=(float s) {
    r *= s;
    g *= s;
    b *= s;
    return *this;
  }
  /// Largest component: the weight used to prune the Whitted tree.
  constexpr float max_component() const { return std::max(r, std::max(g, b)); }
  constexpr bool is_black() const { return r == 0 && g == 0 && b == 0; }
};

constexpr Rgb operator+(const Rgb& a, const Rgb& b) {
  return {a.r + b.r, a.g + b.g, a.b + b.b};
}
constexpr Rgb operator*(const Rgb& a, const Rgb& b) {
  return {a.r * b.r, a.g * b.g, a.b * b.b};
}
constexpr Rgb operator*(const Rgb& a, float s) {
  return {a.r * s, a.g * s, a.b * s};
}
constexpr Rgb operator*(float s, const Rgb& a) {
  return {a.r * s, a.g * s, a.b * s};
}
constexpr bool operator==(const Rgb& a, const Rgb& b) {
  return a.r == b.r && a.g == b.g && a.b == b.b;
}

}  // namespace thaw::render
