#pragma once
// Exact dielectric Fresnel reflectance for unpolarised light and Snell refraction (Hecht, Optics,
// 5th ed., sec. 4.6; pbrt-v4 FrDielectric / Refract). eta is the relative index n_to / n_from.
// Not Schlick's approximation: it is off by up to 0.46 at ice|water grazing angles.
#include <algorithm>
#include <cmath>

#include "render/math/vec3.h"

namespace thaw::render {

/// Reflectance of a smooth interface for a ray arriving at cos(theta_i) = `cos_i` (> 0, measured
/// on the incident side) and relative index `eta` = n_to / n_from. Returns 1 under total
/// internal reflection.
inline float fresnel_dielectric(float cos_i, float eta) {
  cos_i = std::clamp(cos_i, 0.0f, 1.0f);
  const float sin2_i = 1.0f - cos_i * cos_i;
  const float sin2_t = sin2_i / (eta * eta);
  if (sin2_t >= 1.0f) return 1.0f;
  const float cos_t = std::sqrt(std::max(0.0f, 1.0f - sin2_t));
  const float r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (r_parl * r_parl + r_perp * r_perp);
}

/// Refracts the unit incident direction `d` at a surface with unit normal `n` facing the incident
/// side (dot(d, n) < 0), relative index `eta` = n_to / n_from. Returns false under total internal
/// reflection. The result is a unit vector.
inline bool refract(const Vec3& d, const Vec3& n, float eta, Vec3& out) {
  const float cos_i = -dot(d, n);
  const float inv_eta = 1.0f / eta;
  const float sin2_t = inv_eta * inv_eta * std::max(0.0f, 1.0f - cos_i * cos_i);
  if (sin2_t >= 1.0f) return false;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  out = d * inv_eta + n * (inv_eta * cos_i - cos_t);
  return true;
}

}  // namespace thaw::render
