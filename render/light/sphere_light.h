#pragma once
// A spherical area light: a sphere of uniform radiance L = I / (pi r^2) (colour * intensity I,
// radius r). Seen from a point p at distance d > r it covers the cone of half-angle
// theta_max = asin(r / d); sample_sphere_light() draws directions uniformly in that cone
// (pbrt-v4 Sphere::Sample(ctx), PBR 4th ed. sec. 6.2.4), so the direct light at p is estimated
// by L cos(theta_i) V / pdf with pdf = 1 / (2 pi (1 - cos theta_max)).
// Units: fully above p's horizon the sphere gives E = pi L sin^2(theta_max) cos(theta) =
// I cos(theta) / d^2 exactly (Nusselt's analogue), the irradiance of a point light of intensity
// I at its centre with falloff = "inverse_square". falloff = "none" (POV-Ray's convention for a
// point light, E = I cos(theta)) multiplies every sample by d^2, d = distance to the centre: the
// same image as a point light without falloff where the light is unoccluded and small, with soft
// shadows and the horizon handled by the samples. Knows nothing about scenes or occlusion.
#include <cstdint>

#include "render/math/color.h"
#include "render/math/vec3.h"
#include "render/sampling/pixel_sampler.h"

namespace thaw::render {

struct SphereLight {
  Vec3 center;
  /// [scene units], > 0
  float radius = 1.0f;
  /// emitted radiance L = colour * intensity / (pi r^2)
  Rgb radiance;
  /// false: falloff = "none" (see above)
  bool inverse_square = true;
  /// shadow rays per shading point and camera sample
  int samples = 4;
  /// index of its visible sphere's emissive material (radiance L) in Scene::materials()
  std::uint32_t material = 0;
};

struct SphereLightSample {
  /// unit direction from the shaded point towards the sampled point on the sphere
  Vec3 wi;
  /// distance from the shaded point to the sampled point on the sphere [scene units]
  float distance = 0;
  /// solid-angle density of wi [1/sr]
  float pdf = 0;
  /// 1, or d_centre^2 for falloff = "none": the factor on L
  float falloff_scale = 1;
  /// L * falloff_scale: what the estimator multiplies by cos / pdf
  Rgb radiance;
};

/// The light's radiance L for colour * intensity `power` [W/sr-like units] and radius [m]:
/// L = I / (pi r^2).
Rgb sphere_light_radiance(const Rgb& intensity, float radius);

/// Irradiance per unit radiance [sr] from a uniform sphere subtending half-angle sigma
/// (sin^2 sigma = r^2 / d^2) on a surface whose normal makes angle theta with the direction to the
/// centre: pi sin^2(sigma) cos(theta) when the sphere is above the horizon, Snyder's closed form
/// when the horizon cuts it (Snyder 1996, "Area light sources for real-time graphics",
/// MSR-TR-96-11; Lagarde & de Rousiers 2014, "Moving Frostbite to PBR", eq. 19), 0 below.
double sphere_irradiance_per_radiance(double cos_theta, double sin2_sigma);

/// SphereLightSample::falloff_scale of every sample drawn at `p`: 1, or the squared distance to
/// the centre for falloff = "none".
float sphere_light_falloff_scale(const SphereLight& light, const Vec3& p);

/// A direction towards the light from `p`, uniform in the solid angle of the visible cap, from
/// the unit square point `u`. False when p lies inside (or on) the sphere: no light is sampled.
bool sample_sphere_light(const SphereLight& light, const Vec3& p, sampling::Point2 u,
                         SphereLightSample& out);

}  // namespace thaw::render
