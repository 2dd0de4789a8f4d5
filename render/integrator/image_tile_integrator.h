#pragma once
// The image loop of every integrator, written once (pbrt-v4's ImageTileIntegrator): the image is
// cut into square tiles rendered in parallel (OpenMP, dynamic schedule: tiles differ in cost);
// each pixel's camera samples come from a StratifiedPixelSampler with the pixel's own random
// stream, so the image does not depend on the thread count; the progress callback is told after
// every tile. Per pixel:
//   worker.start_pixel(rng)                       the integrator's per-pixel draws, if any
//   for each sample s: value += worker.sample(camera ray through the sample position, s, rng)
//   image(x, y) = worker.pixel_value(value, samples)   film: the box filter's mean (RGB), ...
// Sample positions, sample counts and the reconstruction filter are decided here (the
// per-pixel sample loop in render_image_tiles()); the radiance of a camera ray, in the worker.
// A Worker (one per thread, made by make_worker()) provides: a type Sample (default-constructible
// to zero, +=), start_pixel(Pcg32&), Sample sample(const Ray&, int s, Pcg32&),
// Rgb pixel_value(const Sample& sum, int samples), add_counts(RenderStats&).
// Knows nothing about shading.
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>

#include "render/integrator/render_result.h"
#include "render/integrator/stratified_pixel_sampler.h"
#include "render/scene/scene.h"
#include "src/common/progress.h"

namespace thaw::render {

template <class MakeWorker>
RenderResult render_image_tiles(const Scene& scene, const RenderOptions& options,
                                const ProgressCallback& progress, MakeWorker&& make_worker) {
  const auto start = std::chrono::steady_clock::now();
  const ImageSettings& st = scene.settings();
  const int w = st.width, h = st.height, spp = st.samples_per_pixel;
  const int tile = std::max(1, options.tile_size);
  const int tiles_x = (w + tile - 1) / tile, tiles_y = (h + tile - 1) / tile;
  const int tiles = tiles_x * tiles_y;
  RenderResult result;
  result.image = Image(w, h);
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  std::atomic<std::int64_t> tiles_done{0};
  RenderStats counts;
#pragma omp parallel num_threads(threads)
  {
    auto worker = make_worker();
    using Sample = typename decltype(worker)::Sample;
    StratifiedPixelSampler sampler(spp, w, options.seed);
#pragma omp for schedule(dynamic, 1)
    for (int t = 0; t < tiles; ++t) {
      const int x0 = (t % tiles_x) * tile, y0 = (t / tiles_x) * tile;
      const int x1 = std::min(x0 + tile, w), y1 = std::min(y0 + tile, h);
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
          sampler.start_pixel(x, y);
          worker.start_pixel(sampler.rng());
          Sample sum{};
          for (int s = 0; s < spp; ++s) {
            const auto [sx, sy] = sampler.position(s);
            sum += worker.sample(scene.camera().generate(float(x) + sx, float(y) + sy), s,
                                 sampler.rng());
          }
          result.image.at(x, y) = worker.pixel_value(sum, spp);
        }
      }
      const std::int64_t done = ++tiles_done;
      if (progress) {
        try {
          progress(done, tiles);
        } catch (...) {
          // A progress display must never abort a render (and nothing may leave an OpenMP loop).
        }
      }
    }
#pragma omp critical(thaw_render_counts)
    worker.add_counts(counts);
  }
  result.stats = counts;
  result.stats.threads = threads;
  result.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.stats.rays_per_second =
      result.stats.seconds > 0 ? double(result.stats.rays) / result.stats.seconds : 0.0;
  return result;
}

}  // namespace thaw::render
