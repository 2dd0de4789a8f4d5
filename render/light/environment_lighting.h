#pragma once
// Light from the environment (sky, lat-long map) on matte and phong surfaces, for
// `[environment] light_surfaces = true`: the irradiance E = integral of L_env(w) V(w) cos dw at a
// shading point, which the integrator reflects with the Lambertian BRDF albedo / pi (a white
// floor in a uniform surround of radiance L shows L: the white furnace). Noise-free where nothing
// opaque can hide the sky:
// - unoccluded, E comes from the environment's order-2 spherical harmonics (irradiance_sh.h);
// - sphere lights are opaque: the solid angle of each is taken out analytically (its cap's
//   exact irradiance per unit radiance, Snyder's form at the horizon, times the environment's
//   radiance towards its centre), so nothing is counted twice: that cone holds the light;
// - dielectrics let the environment through: a non-absorbing dielectric conserves radiance along
//   every path, so in a uniform surround it changes no irradiance at all (the furnace), and in a
//   smooth sky it redistributes it over the gradient only; this neglects the Fresnel share
//   reflected back (4-10 % for ice) and the focusing of bright panels;
// - other opaque objects (matte, metal, emissive spheres, boxes, meshes, planes) are found by
//   stratified low-discrepancy shadow rays only where their bounds reach above the point's
//   tangent plane; the visible share of the cosine-distributed samples, weighted by the
//   environment's luminance, scales E (a ratio estimator, exact where all or none are seen).
// Knows nothing about materials or the image.
#include <cstdint>
#include <vector>

#include "render/light/light_sampling.h"
#include "render/math/aabb.h"
#include "render/scene/scene.h"

namespace thaw::render {

/// What can hide the environment from a surface point: the scene's opaque objects other than
/// sphere lights, as bounding boxes and planes. Built once per frame and shared read-only.
class EnvironmentOccluders {
 public:
  explicit EnvironmentOccluders(const Scene& scene);

  /// Whether some occluder may lie above the tangent plane through `origin` with unit normal n
  /// (the shaded object `object` itself is skipped when convex: a sphere or a box cannot hide
  /// its own sky). Conservative: false means no ray of the hemisphere can be blocked.
  bool may_occlude(const Vec3& origin, const Vec3& n, std::uint32_t object) const;

  /// Whether `ray` (unit direction) meets an occluder before leaving the scene: dielectrics and
  /// sphere lights are passed through.
  bool occluded(const Scene& scene, Ray ray) const;

 private:
  struct Bounds {
    Aabb box;
    std::uint32_t object;
    bool convex;
  };
  const std::vector<SceneObject>& m_objects;
  std::vector<Bounds> m_bounds;
  /// opaque planes: object index
  std::vector<std::uint32_t> m_planes;
  /// per object: whether it hides the environment
  std::vector<char> m_occluder;
};

/// Irradiance from the environment at point p (rounding bound p_error, normals ng and ns facing
/// the side being lit) on object `object`, tree level `depth`, camera sample `ctx`. Shadow rays
/// use the pixel sampler's dimension pair after the sphere lights' (light_dimension(depth,
/// number of sphere lights)): for camera sample s, points s n .. s n + n - 1 with n =
/// occlusion_samples (the first n of all camera samples of a pixel form one net: stratified
/// across the pixel), and where they are neither all seen nor all hidden, N - n more, points
/// s N + n .. s N + N - 1 (N = penumbra_samples(n)) of the penumbra pair (+
/// kPenumbraDimensionOffset), as the sphere lights' shadow rays. `rays` counts them.
Rgb environment_irradiance(const Scene& scene, const EnvironmentOccluders& occluders, const Vec3& p,
                           const Vec3& p_error, const Vec3& ng, const Vec3& ns,
                           std::uint32_t object, int depth, const CameraSampleContext& ctx,
                           std::uint64_t& rays);

}  // namespace thaw::render
