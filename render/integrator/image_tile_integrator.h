#pragma once
// The image loop of every integrator, written once (pbrt-v4's ImageTileIntegrator): the image is
// cut into square tiles rendered in parallel (OpenMP, dynamic schedule: tiles differ in cost);
// the progress callback is told after every tile. Per pixel, render/film/adaptive_pixel.h takes
// the camera samples: offsets drawn from the reconstruction filter ([image] filter) with the
// pixel's own Owen-scrambled Sobol points (render/sampling/pixel_sampler.h, seeded by the pixel
// and RenderOptions::seed only), min_samples first and more while the pair-difference error
// metric says the pixel varies, up to samples_per_pixel; a cap of one sample is the pixel centre
// (POV-Ray, and every image rendered before anti-aliasing). Then pixels below the cap that stand
// out of all their neighbours are looked at again with twice their samples, in rounds
// (adaptive_pixel.h, stands_out: specks where a lone agreeing pair misled). The same points drive
// the light samples of each camera sample (render/light/light_sampling.h). The worker's own random
// draws (wavelengths) come from the pixel's PCG32 stream (sequence = pixel index). Nothing depends
// on the thread count, the tile size or the order: a static scene renders the same image every
// time.
//   worker.start_pixel(rng)                              the integrator's per-pixel draws
//   worker.sample(camera ray, CameraSampleContext, rng)  one camera sample's value
//   image(x, y) = worker.pixel_value(weighted mean, 1)   film: RGB, or the spectral ratio
// A Worker (one per thread, made by make_worker()) provides: a type Sample (default-constructible
// to zero, +=, * float), start_pixel(Pcg32&), Sample sample(const Ray&, const
// CameraSampleContext&, Pcg32&), Rgb pixel_value(const Sample& sum, int samples),
// add_counts(RenderStats&). Knows nothing about shading.
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "base/interrupt.h"
#include "base/progress.h"
#include "render/film/adaptive_pixel.h"
#include "render/integrator/render_result.h"
#include "render/light/light_sampling.h"
#include "render/math/rng.h"
#include "render/sampling/pixel_sampler.h"
#include "render/scene/scene.h"

namespace thaw::render {

/// The film's anti-aliasing settings of `st` (render/film/adaptive_pixel.h).
inline AntialiasingSettings antialiasing_settings(const ImageSettings& st) {
  AntialiasingSettings aa;
  aa.max_samples = st.samples_per_pixel;
  aa.adaptive = st.adaptive;
  aa.min_samples = st.min_samples;
  aa.threshold = static_cast<float>(st.adaptive_threshold);
  aa.exposure_scale = static_cast<float>(std::exp2(st.exposure));
  return aa;
}

/// Whether pixel (x, y) of `image` stands out of its neighbours (adaptive_pixel.h, stands_out).
inline bool pixel_stands_out(const Image& image, int x, int y, const AntialiasingSettings& aa) {
  constexpr float inf = std::numeric_limits<float>::infinity();
  const Rgb c = image.at(x, y);
  Rgb highest{-inf, -inf, -inf}, lowest{inf, inf, inf};
  // Bits: c above every neighbour so far in r, g, b, then below in r, g, b. Most pixels are no
  // extremum: the scan stops once no bit is left (after two or three neighbours), before the
  // display values are looked at.
  unsigned open = 0x3f;
  int count = 0;
  for (int ny = std::max(y - 1, 0); ny <= std::min(y + 1, image.height() - 1) && open; ++ny) {
    for (int nx = std::max(x - 1, 0); nx <= std::min(x + 1, image.width() - 1) && open; ++nx) {
      if (nx == x && ny == y) continue;
      const Rgb& n = image.at(nx, ny);
      open &= unsigned(c.r > n.r) | unsigned(c.g > n.g) << 1 | unsigned(c.b > n.b) << 2 |
              unsigned(c.r < n.r) << 3 | unsigned(c.g < n.g) << 4 | unsigned(c.b < n.b) << 5;
      highest = {std::max(highest.r, n.r), std::max(highest.g, n.g), std::max(highest.b, n.b)};
      lowest = {std::min(lowest.r, n.r), std::min(lowest.g, n.g), std::min(lowest.b, n.b)};
      ++count;
    }
  }
  // Still open: every neighbour was scanned, so highest and lowest are complete.
  return count > 0 && open != 0 && stands_out(c, highest, lowest, aa);
}

template <class MakeWorker>
RenderResult render_image_tiles(const Scene& scene, const RenderOptions& options,
                                const ProgressCallback& progress, MakeWorker&& make_worker) {
  const auto start = std::chrono::steady_clock::now();
  const ImageSettings& st = scene.settings();
  const int w = st.width, h = st.height;
  const int tile = std::max(1, options.tile_size);
  const int tiles_x = (w + tile - 1) / tile, tiles_y = (h + tile - 1) / tile;
  const int tiles = tiles_x * tiles_y;
  RenderResult result;
  // Every tile writes each of its pixels once (black when skipped), in parallel: no serial
  // zeroing of the image first.
  result.image = Image(w, h, Image::ForOverwrite{});
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  std::atomic<std::int64_t> tiles_done{0};
  RenderStats counts;
  const Filter filter(st.filter, st.filter_radius);
  const AntialiasingSettings aa = antialiasing_settings(st);
  const auto skipped = [&] {
    return interrupt_requested() ||
           (options.cancel && options.cancel->load(std::memory_order_relaxed));
  };
  const auto index = [w](int x, int y) { return std::size_t(y) * std::size_t(w) + std::size_t(x); };
  // Samples each pixel's estimate holds (adaptive films with room above the first batch only).
  const bool second_looks = aa.adaptive && first_batch(aa) < aa.max_samples;
  std::vector<std::uint32_t> samples(second_looks ? std::size_t(w) * std::size_t(h) : 0u);
  // One pass over the tiles: pixel (x, y) is estimated with settings(x, y), or left as it is
  // where that is nullopt. Returns the samples added to the image.
  const auto pass = [&](auto&& settings, bool report) {
    std::uint64_t added = 0;
    // A local of this lambda for the sample lambda below: clang (14, Debian 12) rejects a lambda
    // inside an OpenMP region of a generic lambda that names the enclosing function's `scene`.
    const Camera& camera = scene.camera();
#pragma omp parallel num_threads(threads) reduction(+ : added)
    {
      auto worker = make_worker();
      using Sample = typename decltype(worker)::Sample;
#pragma omp for schedule(dynamic, 1)
      for (int t = 0; t < tiles; ++t) {
        // After SIGINT/SIGTERM the remaining tiles are skipped; the caller checks and writes
        // nothing. Cancelled (RenderOptions::cancel): skipped too; the caller discards the image.
        const int x0 = (t % tiles_x) * tile, y0 = (t / tiles_x) * tile;
        const int x1 = std::min(x0 + tile, w), y1 = std::min(y0 + tile, h);
        if (skipped()) {
          if (report)
            for (int y = y0; y < y1; ++y)
              for (int x = x0; x < x1; ++x) result.image.at(x, y) = Rgb{};
          continue;
        }
        for (int y = y0; y < y1; ++y) {
          for (int x = x0; x < x1; ++x) {
            const std::optional<AntialiasingSettings> pixel_aa = settings(x, y);
            if (!pixel_aa) continue;
            Pcg32 rng(std::uint64_t(y) * std::uint64_t(w) + std::uint64_t(x), options.seed);
            worker.start_pixel(rng);
            const sampling::PixelSampler points(x, y, options.seed);
            const PixelEstimate<Sample> e = estimate_pixel<Sample>(
                x, y, points, filter, *pixel_aa,
                [&](float fx, float fy, std::uint32_t s) {
                  return worker.sample(camera.generate(fx, fy), CameraSampleContext{&points, s},
                                       rng);
                },
                [&](const Sample& v) { return worker.pixel_value(v, 1); });
            result.image.at(x, y) = worker.pixel_value(e.value, 1);
            if (second_looks) {
              // The image holds this estimate's samples instead of the earlier one's.
              added += static_cast<std::uint64_t>(e.samples) - samples[index(x, y)];
              samples[index(x, y)] = static_cast<std::uint32_t>(e.samples);
            } else {
              added += static_cast<std::uint64_t>(e.samples);
            }
          }
        }
        const std::int64_t done = ++tiles_done;
        if (report && progress) {
          try {
            progress(done, tiles);
          } catch (...) {
            // A progress display must never abort a render (nothing may leave an OpenMP loop).
          }
        }
      }
#pragma omp critical(thaw_render_counts)
      worker.add_counts(counts);
    }
    return added;
  };
  std::uint64_t camera_samples =
      pass([&](int, int) { return std::optional<AntialiasingSettings>(aa); }, true);
  // Second looks (render/film/adaptive_pixel.h, stands_out): a pixel below the cap that stands
  // out of all its neighbours is estimated again with its first batch doubled (the same samples
  // first, then more while they vary), and again while it still stands out, up to the cap. Every
  // round decides on the whole image as the previous round left it, before any pixel changes:
  // nothing depends on the order, the tiles or the threads. The first round looks at every
  // pixel, later ones at those the round before re-estimated (only they changed).
  std::vector<std::uint8_t> look(samples.size(), 1);
  for (bool any = second_looks; any && !skipped();) {
    any = false;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(|| : any)
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        if (!look[index(x, y)]) continue;
        const bool again = samples[index(x, y)] < std::uint32_t(aa.max_samples) &&
                           pixel_stands_out(result.image, x, y, aa);
        look[index(x, y)] = again ? 1 : 0;
        any = any || again;
      }
    }
    if (!any) break;
    camera_samples += pass(
        [&](int x, int y) -> std::optional<AntialiasingSettings> {
          if (!look[index(x, y)]) return std::nullopt;
          return doubled_first_batch(aa, int(samples[index(x, y)]));
        },
        false);
  }
  result.stats = counts;
  result.stats.camera_samples = camera_samples;
  result.stats.threads = threads;
  result.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.stats.rays_per_second =
      result.stats.seconds > 0 ? double(result.stats.rays) / result.stats.seconds : 0.0;
  return result;
}

}  // namespace thaw::render
