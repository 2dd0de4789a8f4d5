#pragma once
// One pixel's value from camera samples, with adaptive anti-aliasing: a few low-discrepancy
// samples everywhere, more where the pixel varies, up to a cap.
//   - Samples come in power-of-two batches (min_samples, then doubling: 4, 8, 16, ... up to
//     max_samples), so every stopping point is a (0,m,2)-net of the pixel sampler.
//   - After each batch the standard error of the pixel's mean is estimated in display space
//     (each sample's channels exposed, clamped to [0, 1] and sRGB-encoded, as the PNG will show
//     them) from the differences within pairs of samples (2k, 2k+1): s^2 = mean of (a - b)^2 / 2,
//     error = s / sqrt(n). Both samples of a pair carry the same wavelengths in a spectral render
//     (render/integrator/spectral_whitted.cpp), so the estimate measures how the image varies
//     over the pixel (edges, texture, penumbrae), not the colour noise of wavelength sampling,
//     which more samples of the pixel would not remove (it is shared by all pixels: banding).
//     Sampling stops once the largest channel's error is at most `threshold` (display units,
//     1/255 = one 8-bit step). The plain-Monte-Carlo bound is conservative for these samples.
//   - Offsets within the pixel are drawn from the reconstruction filter (render/film/filter.h);
//     with a cap of one sample the ray goes through the pixel centre (POV-Ray; today's images).
// A pixel's samples depend only on the pixel (render/sampling/pixel_sampler.h), so the image is
// the same for any thread count and tile order. Knows nothing about scenes or rays.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "render/film/filter.h"
#include "render/math/color.h"
#include "render/sampling/pixel_sampler.h"

namespace thaw::render {

struct AntialiasingSettings {
  /// [image] samples_per_pixel: the cap
  int max_samples = 1;
  /// [image] adaptive; off: every pixel takes max_samples
  bool adaptive = false;
  /// [image] min_samples: the first batch (>= 2: one pair)
  int min_samples = 4;
  /// [image] adaptive_threshold: display-space standard error at which a pixel stops
  float threshold = 0.01f;
  /// 2^exposure, applied before the display transform of the error metric
  float exposure_scale = 1.0f;
};

/// The sampler dimension of the film position (dimension pair 0).
inline constexpr std::uint32_t kFilmDimension = 0;

/// Display value of a linear channel: exposed, clamped, sRGB-encoded (IEC 61966-2-1).
inline float display_value(float linear, float exposure_scale) {
  const float v = std::clamp(linear * exposure_scale, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

template <class Value>
struct PixelEstimate {
  Value value{};
  int samples = 0;
};

/// Estimates pixel (x, y). `radiance(film_x, film_y, sample_index)` returns a Value (a sum-able
/// type with `* float`) for the camera ray through continuous image position (film_x, film_y)
/// [pixels]; `to_rgb(value)` gives its linear RGB for the error metric.
template <class Value, class Radiance, class ToRgb>
PixelEstimate<Value> estimate_pixel(int x, int y, const sampling::PixelSampler& sampler,
                                    const Filter& filter, const AntialiasingSettings& aa,
                                    Radiance&& radiance, ToRgb&& to_rgb) {
  PixelEstimate<Value> out;
  const float cx = float(x) + 0.5f, cy = float(y) + 0.5f;
  if (aa.max_samples <= 1) {
    out.value = radiance(cx, cy, 0u);
    out.samples = 1;
    return out;
  }
  Value sum{};
  // Sum over completed pairs of the squared display-value differences, per channel.
  std::array<double, 3> pair_sq{0, 0, 0}, first{0, 0, 0};
  int n = 0;
  int batch_end = aa.adaptive ? std::min(aa.min_samples, aa.max_samples) : aa.max_samples;
  while (true) {
    // The last batch's display values would feed no decision: not computed (3 pow per sample;
    // half the samples of the pixels that reach the cap).
    const bool last = batch_end >= aa.max_samples;
    for (; n < batch_end; ++n) {
      const auto index = static_cast<std::uint32_t>(n);
      const FilterSample fs = filter.sample(sampler.get_2d(index, kFilmDimension));
      const Value v = radiance(cx + fs.dx, cy + fs.dy, index);
      sum += v * fs.weight;
      if (last) continue;
      const Rgb c = to_rgb(v);
      const std::array<double, 3> d{display_value(c.r, aa.exposure_scale),
                                    display_value(c.g, aa.exposure_scale),
                                    display_value(c.b, aa.exposure_scale)};
      for (int k = 0; k < 3; ++k) {
        if (n % 2 == 0)
          first[k] = d[k];
        else
          pair_sq[k] += (d[k] - first[k]) * (d[k] - first[k]);
      }
    }
    if (batch_end >= aa.max_samples) break;
    const double variance = std::max({pair_sq[0], pair_sq[1], pair_sq[2]}) / (2.0 * (n / 2));
    if (std::sqrt(variance / n) <= aa.threshold) break;
    batch_end = std::min(2 * batch_end, aa.max_samples);
  }
  out.value = sum * (1.0f / float(n));
  out.samples = n;
  return out;
}

}  // namespace thaw::render
