#pragma once
// Direct light from a scene's sphere lights at a surface point, by stratified low-discrepancy
// samples with shadow rays: what soft shadows are made of. For camera sample s of a pixel, light
// k takes n = light.samples directions, the points s n .. s n + n - 1 of the pixel sampler's
// dimension pair `dimension_base + k`: for a power-of-two n each shading point's set is a
// (0,log2 n,2)-net, and all camera samples of the pixel together form one larger net. The
// integrator supplies the BSDF through a callback, so RGB and spectral shading share this.
// Knows nothing about materials or the image.
#include <cstdint>

#include "render/light/sphere_light.h"
#include "render/sampling/pixel_sampler.h"
#include "render/scene/scene.h"

namespace thaw::render {

/// Where the sampler is for one camera sample: the pixel's sampler and the sample's index.
struct CameraSampleContext {
  const sampling::PixelSampler* sampler = nullptr;
  std::uint32_t sample_index = 0;
};

/// Dimension pair of light k at Whitted tree level `depth` (1 = camera ray): every shading event
/// on a path gets its own pairs, distinct from the film's (pair 0).
inline std::uint32_t light_dimension(int depth, std::size_t light) {
  return 1u + static_cast<std::uint32_t>(depth) * 64u + static_cast<std::uint32_t>(light % 64u);
}

/// For each unoccluded sample towards each sphere light from point p (rounding bound p_error,
/// geometric normal ng facing the side being lit): `shade(light_index, wi, weight)`, where the
/// light's contribution is BSDF * |cos| * L_light * weight, weight = falloff_scale / (pdf * n).
/// Samples below the geometric horizon are skipped without a shadow ray. `rays` counts the
/// shadow rays traced.
template <class Shade>
void sample_sphere_lights(const Scene& scene, const Vec3& p, const Vec3& p_error, const Vec3& ng,
                          int depth, const CameraSampleContext& ctx, std::uint64_t& rays,
                          Shade&& shade) {
  const auto& lights = scene.sphere_lights();
  for (std::size_t k = 0; k < lights.size(); ++k) {
    const SphereLight& light = lights[k];
    const auto n = static_cast<std::uint32_t>(light.samples);
    const std::uint32_t dim = light_dimension(depth, k);
    for (std::uint32_t j = 0; j < n; ++j) {
      SphereLightSample s;
      if (!sample_sphere_light(light, p, ctx.sampler->get_2d(ctx.sample_index * n + j, dim), s))
        break;
      if (dot(s.wi, ng) <= 0.0f) continue;
      const Vec3 origin = offset_ray_origin(p, p_error, ng, s.wi);
      // Stop just short of the point sampled on the light's own (visible, opaque) sphere.
      const Ray shadow{origin, s.wi, length(p + s.wi * s.distance - origin) * (1.0f - 1e-4f)};
      ++rays;
      if (scene.occluded(shadow)) continue;
      shade(k, s.wi, s.falloff_scale / (s.pdf * float(n)));
    }
  }
}

}  // namespace thaw::render
