#pragma once
// Tiny 3-vector value types for the renderer (header-only, float, no Eigen).
// Vec3 is the one geometric type (points, directions and normals are all Vec3; the functions that
// need a distinction say which in their names and comments). Knows nothing about rays or scenes.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace thaw::render {

struct Vec3 {
  float x = 0, y = 0, z = 0;

  constexpr Vec3() = default;
  constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}

  constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

  constexpr Vec3 operator-() const { return {-x, -y, -z}; }
  constexpr Vec3& operator+=(const Vec3& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  constexpr Vec3& operator-=(const Vec3& o) {
    x -= o.x;
    y -= o.y;
    z -= o.z;
    return *this;
  }
  constexpr Vec3& operator*=(float s) {
    x *= s;
    y *= s;
    z *= s;
    return *this;
  }
};

constexpr Vec3 operator+(const Vec3& a, const Vec3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
constexpr Vec3 operator-(const Vec3& a, const Vec3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
constexpr Vec3 operator*(const Vec3& a, float s) {
  return {a.x * s, a.y * s, a.z * s};
}
constexpr Vec3 operator*(float s, const Vec3& a) {
  return {a.x * s, a.y * s, a.z * s};
}
constexpr Vec3 operator/(const Vec3& a, float s) {
  return a * (1.0f / s);
}
/// Component-wise product.
constexpr Vec3 mul(const Vec3& a, const Vec3& b) {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
constexpr bool operator==(const Vec3& a, const Vec3& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

constexpr float dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(const Vec3& a) {
  return std::sqrt(dot(a, a));
}
inline Vec3 normalize(const Vec3& a) {
  return a / length(a);
}
inline Vec3 abs(const Vec3& a) {
  return {std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)};
}
inline Vec3 min(const Vec3& a, const Vec3& b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3 max(const Vec3& a, const Vec3& b) {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
inline int max_dimension(const Vec3& a) {
  return (a.x > a.y) ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
}
/// Flips `n` so that it lies in the hemisphere of `v` (pbrt FaceForward).
inline Vec3 face_forward(const Vec3& n, const Vec3& v) {
  return dot(n, v) < 0.0f ? -n : n;
}

/// Mirror reflection of the incident direction `d` about the unit normal `n`.
inline Vec3 reflect(const Vec3& d, const Vec3& n) {
  return d - n * (2.0f * dot(d, n));
}

/// gamma(n) = n u / (1 - n u), u = 2^-24: the bound on relative rounding error of n float
/// operations (Higham; pbrt-v4 util/float.h `gamma`).
constexpr float gamma_bound(int n) {
  constexpr float u = 0.5f * 1.1920928955078125e-7f;
  return (static_cast<float>(n) * u) / (1.0f - static_cast<float>(n) * u);
}

/// Next float up / down (pbrt-v4 NextFloatUp/Down, by stepping the bit pattern: inline, unlike
/// std::nextafter), used to push ray origins off surfaces.
inline float next_float_up(float v) {
  if (std::isinf(v) && v > 0.0f) return v;
  if (v == -0.0f) v = 0.0f;
  auto bits = std::bit_cast<std::uint32_t>(v);
  bits = v >= 0.0f ? bits + 1 : bits - 1;
  return std::bit_cast<float>(bits);
}
inline float next_float_down(float v) {
  if (std::isinf(v) && v < 0.0f) return v;
  if (v == 0.0f) v = -0.0f;
  auto bits = std::bit_cast<std::uint32_t>(v);
  bits = v > 0.0f ? bits - 1 : bits + 1;
  return std::bit_cast<float>(bits);
}

}  // namespace thaw::render
