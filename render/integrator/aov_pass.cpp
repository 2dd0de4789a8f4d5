#include "render/integrator/aov_pass.h"

#include <omp.h>

namespace thaw::render {
namespace {

/// Depth, normal and ids of the first surface along the ray through (x, y) into pixel `i`.
void shade_centre(const Scene& scene, const Vec3& forward, float x, float y, std::size_t i,
                  AovImage& aov) {
  const Ray ray = scene.camera().generate(x, y);
  Hit hit;
  if (!scene.intersect(ray, hit)) return;
  const SurfaceInteraction si = scene.interaction(ray, hit);
  // Camera-space z: the ray's length t (unit direction) projected on the view axis.
  aov.depth[i] = hit.t * dot(ray.direction, forward);
  aov.normal[i] = si.ns;
  aov.object_id[i] = si.object + 1;
  const SceneObject& object = scene.objects()[si.object];
  if (object.dielectric)  // the side the ray enters: inside if it meets the outward normal head-on
    aov.medium_id[i] = (dot(ray.direction, si.ng) < 0.0f ? object.inside : object.outside) + 1;
}

}  // namespace

AovImage render_aovs(const Scene& scene, int threads) {
  const int w = scene.settings().width, h = scene.settings().height;
  AovImage aov(w, h);
  for (const SceneObject& o : scene.objects()) aov.object_names.push_back(o.label);
  for (const Medium& m : scene.media()) aov.medium_names.push_back(m.name);
  // The view axis is the direction through the image centre (render/scene/camera.h maps the
  // centre (w/2, h/2) to the look-at direction).
  const Vec3 forward = scene.camera().generate(0.5f * w, 0.5f * h).direction;
  const Rgb bg = scene.background();
  const bool black_background = bg.r == 0.0f && bg.g == 0.0f && bg.b == 0.0f;
#pragma omp parallel for schedule(dynamic, 4) \
    num_threads(threads > 0 ? threads : omp_get_max_threads())
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      shade_centre(scene, forward, x + 0.5f, y + 0.5f, i, aov);
      if (!black_background) continue;
      int covered = 0;
      for (int s = 0; s < 4; ++s) {
        Hit hit;
        covered += scene.intersect(
            scene.camera().generate(x + 0.25f + 0.5f * (s & 1), y + 0.25f + 0.5f * (s >> 1)), hit);
      }
      aov.alpha[i] = 0.25f * static_cast<float>(covered);
    }
  return aov;
}

}  // namespace thaw::render
