#pragma once
// Direct light from a scene's sphere lights at a surface point, by stratified low-discrepancy
// samples with shadow rays: what soft shadows are made of. For camera sample s of a pixel, light
// k takes n = light.samples directions, the points s n .. s n + n - 1 of the pixel sampler's
// dimension pair light_dimension(depth, k): for a power-of-two n each shading point's set is a
// (0,log2 n,2)-net, and the first n of all camera samples of the pixel together (points
// 0 .. S n - 1) form one larger net, so the pixel's estimate is stratified too. Penumbra samples
// come from a second pair (+ kPenumbraDimensionOffset), points s N + n .. s N + N - 1. The
// integrator supplies the BSDF through a callback, so RGB and spectral shading share this.
// Knows nothing about materials or the image.
#include <algorithm>
#include <array>
#include <cmath>
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

/// Shadow samples a shading point takes in a penumbra, where its first n samples are neither all
/// seen nor all hidden: 8 n, at most 64 (but never fewer than n). Elsewhere the ratio estimator
/// is exact with the first n, so the extra rays go only where the light is partly hidden.
inline constexpr std::uint32_t kMaxPenumbraSamples = 64;
/// The dimension pair of a light's penumbra samples: its own pair plus this.
inline constexpr std::uint32_t kPenumbraDimensionOffset = 0x10000u;
inline std::uint32_t penumbra_samples(std::uint32_t n) {
  return std::max(n, std::min(8 * n, kMaxPenumbraSamples));
}

/// Direct light from every sphere light at point p (rounding bound p_error, geometric normal ng
/// and shading normal ns facing the side being lit):
///   diffuse(light_index, e)            irradiance E = L_light * e at p (Lambertian term)
///   specular(light_index, wi, weight)  per unoccluded sample: radiance L_light * weight arriving
///                                      along wi, weight = falloff_scale / (pdf * samples taken)
/// The irradiance is the exact unoccluded value (sphere_irradiance_per_radiance, horizon
/// included) times the fraction of the cap's cosine-weighted samples that reach the light:
/// E = E_exact * sum_visible(cos / pdf) / sum_all(cos / pdf), a ratio estimator, consistent, exact
/// wherever the light is wholly visible or wholly hidden (no noise outside penumbrae; a lone
/// unshadowed sphere light gives precisely a point light's I cos / d^2). Samples below the
/// horizon cast no shadow ray. For camera sample s a shading point takes points s n .. s n + n - 1
/// and, in a penumbra, N - n more (N = penumbra_samples(n)), points s N + n .. s N + N - 1 of the
/// penumbra pair. Where something may hide the light (the cone test below) but the first n were
/// all seen, n more look for it before stopping: at a penumbra's outer fringe, where a sliver of
/// the light is hidden, stopping at n seen samples reports the whole light (too bright on
/// average) in some camera samples and the refined fraction in others, a grain of the shadow's
/// edge (docs/benchmarks.md "Penumbra"). `rays` counts the shadow rays.
/// Where no shadow ray can be occluded (Scene::light_unoccluded: the cone from the rays' common
/// origin to the light meets nothing) no ray is cast: every sample would be seen, the fraction is
/// 1, and the result is the same to the bit; without `highlights` (a matte surface) not even the
/// samples are drawn. On the default film this skips most shading points away from the ice.
template <class Diffuse, class Specular>
void sample_sphere_lights(const Scene& scene, const Vec3& p, const Vec3& p_error, const Vec3& ng,
                          const Vec3& ns, int depth, const CameraSampleContext& ctx,
                          std::uint64_t& rays, Diffuse&& diffuse, Specular&& specular,
                          bool highlights = true) {
  const auto& lights = scene.sphere_lights();
  for (std::size_t k = 0; k < lights.size(); ++k) {
    const SphereLight& light = lights[k];
    const Vec3 to_c = light.center - p;
    const double d2 = double(dot(to_c, to_c)), r2 = double(light.radius) * light.radius;
    if (!(d2 > r2)) continue;  // inside the light: no light is sampled
    const double e_unit =
        sphere_irradiance_per_radiance(double(dot(ns, to_c)) / std::sqrt(d2), r2 / d2);
    if (!(e_unit > 0.0)) continue;  // wholly below the horizon
    const auto n = static_cast<std::uint32_t>(light.samples);
    const std::uint32_t n_max = penumbra_samples(n);
    // Every traced ray (dot(wi, ng) > 0) starts from the same offset origin.
    const bool clear = scene.light_unoccluded(offset_ray_origin(p, p_error, ng, ng), k);
    if (clear && !highlights) {
      diffuse(k, static_cast<float>(sphere_light_falloff_scale(light, p) * e_unit));
      continue;
    }
    const std::uint32_t dim = light_dimension(depth, k);
    double all = 0.0, visible = 0.0;
    float falloff_scale = 1.0f;
    int seen = 0, hidden = 0;
    struct Highlight {
      Vec3 wi;
      float weight;
    };
    std::array<Highlight, kMaxPenumbraSamples> highlights;
    std::size_t highlight_count = 0;
    std::uint32_t taken = 0;
    for (std::uint32_t j = 0; j < n_max; ++j, ++taken) {
      // After the first n: on only in a penumbra (some seen, some hidden), or, where something
      // may hide the light but all n were seen, n more to look for it.
      if (j == n && (seen == 0 || (hidden == 0 && clear))) break;
      if (j == 2 * n && hidden == 0) break;
      SphereLightSample s;
      const sampling::Point2 u =
          j < n ? ctx.sampler->get_2d(ctx.sample_index * n + j, dim)
                : ctx.sampler->get_2d(ctx.sample_index * n_max + j, dim + kPenumbraDimensionOffset);
      if (!sample_sphere_light(light, p, u, s)) break;
      falloff_scale = s.falloff_scale;
      const float cos_s = dot(ns, s.wi);
      if (cos_s <= 0.0f || dot(s.wi, ng) <= 0.0f) continue;
      const double f = double(cos_s) / s.pdf;
      all += f;
      const Vec3 origin = offset_ray_origin(p, p_error, ng, s.wi);
      // Stop just short of the point sampled on the light's own (visible, opaque) sphere.
      const Ray shadow{origin, s.wi, length(p + s.wi * s.distance - origin) * (1.0f - 1e-4f)};
      if (!clear) {
        ++rays;
        if (scene.occluded(shadow)) {
          ++hidden;
          continue;
        }
      }
      ++seen;
      visible += f;
      if (highlight_count < highlights.size())
        highlights[highlight_count++] = {s.wi, s.falloff_scale / s.pdf};
      else
        specular(k, s.wi, s.falloff_scale / (s.pdf * float(n)));  // n = N > 64: no refinement
    }
    // The highlight: the plain estimate over the samples taken.
    for (std::size_t i = 0; i < highlight_count; ++i)
      specular(k, highlights[i].wi, highlights[i].weight / float(taken));
    // No sample above the horizon (a sliver of the cap above it): taken as unshadowed.
    const double fraction = all > 0.0 ? visible / all : 1.0;
    if (fraction > 0.0) diffuse(k, static_cast<float>(falloff_scale * e_unit * fraction));
  }
}

}  // namespace thaw::render
