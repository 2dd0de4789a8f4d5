#include "render/light/sphere_light.h"

#include <algorithm>
#include <cmath>

namespace thaw::render {

Rgb sphere_light_radiance(const Rgb& intensity, float radius) {
  constexpr double kPi = 3.14159265358979323846;
  return intensity * static_cast<float>(1.0 / (kPi * double(radius) * double(radius)));
}

double sphere_irradiance_per_radiance(double cos_theta, double sin2_sigma) {
  constexpr double kPi = 3.14159265358979323846;
  if (cos_theta * cos_theta > sin2_sigma) return std::max(0.0, kPi * sin2_sigma * cos_theta);
  const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  const double x = std::sqrt(std::max(0.0, 1.0 / sin2_sigma - 1.0));
  const double y = std::clamp(-x * cos_theta / sin_theta, -1.0, 1.0);
  const double s = sin_theta * std::sqrt(1.0 - y * y);
  // x = 0 (a point on the sphere): the half-space limit, pi (1 + cos) / 2 ... handled by atan.
  const double a = x > 0.0 ? std::atan(s / x) : kPi / 2;
  return std::max(0.0, (cos_theta * std::acos(y) - x * s) * sin2_sigma + a);
}

namespace {
/// Squared distance from p to the light's centre, in double (as the sampling uses it).
double squared_distance(const SphereLight& light, const Vec3& p) {
  const double cx = double(light.center.x) - p.x, cy = double(light.center.y) - p.y,
               cz = double(light.center.z) - p.z;
  return cx * cx + cy * cy + cz * cz;
}
}  // namespace

float sphere_light_falloff_scale(const SphereLight& light, const Vec3& p) {
  return light.inverse_square ? 1.0f : static_cast<float>(squared_distance(light, p));
}

bool sample_sphere_light(const SphereLight& light, const Vec3& p, sampling::Point2 u,
                         SphereLightSample& out) {
  constexpr double kPi = 3.14159265358979323846;
  // Double inside: 1 - cos(theta_max) ~ r^2 / (2 d^2) must not cancel for small or far lights.
  const double cx = double(light.center.x) - p.x, cy = double(light.center.y) - p.y,
               cz = double(light.center.z) - p.z;
  const double d2 = cx * cx + cy * cy + cz * cz, r = light.radius, r2 = r * r;
  if (!(d2 > r2)) return false;
  const double d = std::sqrt(d2);
  const double wx = cx / d, wy = cy / d, wz = cz / d;
  const double sin2_max = r2 / d2;
  const double cos_max = std::sqrt(1.0 - sin2_max);
  const double one_minus_cos_max = sin2_max / (1.0 + cos_max);  // = 1 - cos(theta_max), stably
  // cos(theta) uniform in [cos_max, 1]: 1 - cos = u (1 - cos_max), sin^2 = (1 - cos)(1 + cos).
  const double one_minus_cos = double(u.x) * one_minus_cos_max;
  const double cos_t = 1.0 - one_minus_cos;
  const double sin_t = std::sqrt(std::max(0.0, one_minus_cos * (2.0 - one_minus_cos)));
  const double phi = 2.0 * kPi * double(u.y);
  // Orthonormal frame around w (Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
  const double sign = std::copysign(1.0, wz);
  const double a = -1.0 / (sign + wz), b = wx * wy * a;
  const double ux = 1.0 + sign * wx * wx * a, uy = sign * b, uz = -sign * wx;
  const double vx = b, vy = sign + wy * wy * a, vz = -wy;
  const double sx = sin_t * std::cos(phi), sy = sin_t * std::sin(phi);
  const double dx = sx * ux + sy * vx + cos_t * wx, dy = sx * uy + sy * vy + cos_t * wy,
               dz = sx * uz + sy * vz + cos_t * wz;
  // Nearest intersection with the sphere along the direction, in the cancellation-free form
  // t = (d^2 - r^2) / (d cos + sqrt(r^2 - d^2 sin^2)).
  const double disc = std::max(0.0, r2 - d2 * sin_t * sin_t);
  const double t = (d2 - r2) / (d * cos_t + std::sqrt(disc));
  out.wi = Vec3{static_cast<float>(dx), static_cast<float>(dy), static_cast<float>(dz)};
  out.distance = static_cast<float>(t);
  out.pdf = static_cast<float>(1.0 / (2.0 * kPi * one_minus_cos_max));
  out.falloff_scale = sphere_light_falloff_scale(light, p);
  out.radiance = light.radiance * out.falloff_scale;
  return true;
}

}  // namespace thaw::render
