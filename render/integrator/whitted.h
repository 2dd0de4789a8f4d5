#pragma once
// Whitted ray tracing (Whitted 1980) of a built Scene: direct light from point lights with hard
// shadows, ambient term, mirror reflection, and dielectric interfaces between named media with
// exact Fresnel splitting (R reflected, 1 - R transmitted), Snell refraction and total internal
// reflection. The tree is cut at max_depth and wherever a branch's weight falls below
// min_weight (POV-Ray's adaptive depth control). Every ray carries the medium it travels in; a
// ray reaching an interface from a side whose label differs is counted as a medium mismatch
// (0 on a consistent scene). Parallel over 16x16 tiles (OpenMP, dynamic schedule); each pixel's
// samples come from its own RNG stream, so the image does not depend on the thread count.
// Dielectric surfaces cast full shadows: the light they pass on is a caustic, which Whitted
// tracing cannot find (POV-Ray instead lets light through glass unrefracted, without shadow).
#include <cstdint>

#include "render/image/image.h"
#include "render/scene/scene.h"
#include "src/common/progress.h"

namespace thaw::render {

struct RenderOptions {
  /// OpenMP threads; 0 = the OpenMP default (all cores)
  int threads = 0;
  /// square tile side [pixels]
  int tile_size = 16;
  /// seed of the per-pixel jitter streams
  std::uint64_t seed = 0;
};

struct RenderStats {
  /// camera, reflected, refracted and shadow rays
  std::uint64_t rays = 0;
  /// rays that reached an interface from a side whose medium differs from the one they carry
  std::uint64_t medium_mismatches = 0;
  /// spectral mode: camera samples traced with all [image] dispersion_wavelengths (split)
  std::uint64_t refined_samples = 0;
  /// spectral mode: dispersive refractions integrated over the spectrum (adaptive) and split
  /// into one ray per carried wavelength (split, or adaptive's fallback)
  std::uint64_t adaptive_refractions = 0, split_refractions = 0;
  /// wall time of the tracing [s]
  double seconds = 0;
  double rays_per_second = 0;
  int threads = 0;
};

struct RenderResult {
  /// linear radiance, scene.settings().width x height
  Image image;
  RenderStats stats;
};

/// Renders `scene` at its settings (size, samples, depth). `progress(done, total)` is called with
/// tiles finished (from worker threads; it must be thread-safe and must not throw).
RenderResult render(const Scene& scene, const RenderOptions& options = {},
                    const ProgressCallback& progress = {});

/// Radiance along one ray (for tests): traced as a primary ray starting in `medium`.
Rgb trace_ray(const Scene& scene, const Ray& ray, std::uint32_t medium, RenderStats* stats = nullptr);

}  // namespace thaw::render
