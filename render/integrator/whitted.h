#pragma once
// thaw's integrator: Whitted ray tracing of a built Scene (render/integrator/whitted_shading.h:
// dielectrics with Fresnel, Snell and total internal reflection between named media, metal,
// matte/phong under point lights with hard shadows, emission), over the image loop of
// render/integrator/image_tile_integrator.h (16x16 tiles in parallel, per-pixel random streams:
// the image does not depend on the thread count). render() traces RGB, or hands spectral scenes
// (Scene::spectral(): dispersion, absorption) to render/integrator/spectral_whitted.h; both
// instantiate the same shading. Dielectric surfaces cast full shadows: the light they pass on is
// a caustic, which Whitted tracing cannot find (POV-Ray instead lets light through glass
// unrefracted, without shadow).
#include <cstdint>

#include "base/progress.h"
#include "render/integrator/render_result.h"
#include "render/scene/scene.h"

namespace thaw::render {

/// Renders `scene` at its settings (size, samples, depth). `progress(done, total)` is called with
/// tiles finished (from worker threads; it must be thread-safe and must not throw).
RenderResult render(const Scene& scene, const RenderOptions& options = {},
                    const ProgressCallback& progress = {});

/// Radiance along one ray (for tests): traced as a primary ray starting in `medium`.
Rgb trace_ray(const Scene& scene, const Ray& ray, std::uint32_t medium,
              RenderStats* stats = nullptr);

}  // namespace thaw::render
