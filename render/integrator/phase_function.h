#pragma once
// The Henyey-Greenstein phase function (Henyey and Greenstein 1941) of a scattering medium
// (render/media/scattering.h): p(cos) = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos)^1.5), cos measured
// from the direction of travel, and its exact inversion (pbrt-v4 SampleHenyeyGreenstein). Used by
// the integrators' volume scattering; knows nothing about scenes.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "render/material/microfacet.h"
#include "render/math/vec3.h"

namespace thaw::render {

/// Density over the sphere [1/sr] of leaving at cosine `cos` to the direction of travel.
inline float henyey_greenstein(float cos, float g) {
  const float d = 1.0f + g * g - 2.0f * g * cos;
  return (1.0f - g * g) / (4.0f * std::numbers::pi_v<float> * d * std::sqrt(d));
}

/// Cosine to the direction of travel drawn from p, u in [0, 1).
inline float sample_henyey_greenstein_cos(float g, float u) {
  if (std::abs(g) < 1e-3f) return 1.0f - 2.0f * u;
  const float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u);
  return std::clamp((1.0f + g * g - s * s) / (2.0f * g), -1.0f, 1.0f);
}

/// A new unit direction after scattering unit direction d with asymmetry g (u1: the cosine,
/// u2: the azimuth).
inline Vec3 scatter_henyey_greenstein(const Vec3& d, float g, float u1, float u2) {
  const float c = sample_henyey_greenstein_cos(g, u1);
  const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
  const float phi = 2.0f * std::numbers::pi_v<float> * u2;
  const microfacet::Frame f(d);
  return normalize(f.to_world(Vec3{s * std::cos(phi), s * std::sin(phi), c}));
}

}  // namespace thaw::render
