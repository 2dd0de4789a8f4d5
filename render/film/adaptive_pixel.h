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
//   - One pair's agreement can mislead (stands_out below): a pixel that then stands out of all
//     its neighbours is looked at again with twice its samples, by the image loop, which sees
//     the neighbours.
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

/// The sRGB encoding (IEC 61966-2-1) of a linear value in [0, 1], from the formula.
inline float srgb_encode(float v) {
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

/// srgb_encode at kSrgbTableSize + 1 evenly spaced nodes of [0, 1] (and the last node once more,
/// so that 1 itself interpolates without a branch): display_value reads it instead of calling
/// pow three times a sample (2.7 % of a default-film frame's CPU was powf).
inline constexpr int kSrgbTableSize = 4096;
inline const std::array<float, kSrgbTableSize + 2> kSrgbTable = [] {
  std::array<float, kSrgbTableSize + 2> t{};
  for (int i = 0; i <= kSrgbTableSize; ++i)
    t[std::size_t(i)] = srgb_encode(float(i) / kSrgbTableSize);
  t[kSrgbTableSize + 1] = t[kSrgbTableSize];
  return t;
}();

/// Display value of a linear channel: exposed, clamped, sRGB-encoded, linearly interpolated in
/// kSrgbTable. Error at most h^2/8 max|f''| = 1.8e-5 (h = 1/4096; |f''| peaks at 2366 just above
/// the linear segment) or, in the node interval holding the segment's end, h/4 times the jump
/// of slope there (12.92 - 12.70): 1.4e-5; against adaptive_threshold >= 1e-4. NaN counts as 0.
inline float display_value(float linear, float exposure_scale) {
  const float e = linear * exposure_scale;
  const float v = (e > 0.0f ? std::min(e, 1.0f) : 0.0f) * float(kSrgbTableSize);
  const auto i = static_cast<std::size_t>(v);
  return kSrgbTable[i] + (kSrgbTable[i + 1] - kSrgbTable[i]) * (v - float(i));
}

template <class Value>
struct PixelEstimate {
  Value value{};
  int samples = 0;
};

/// The first batch of an adaptive pixel: min_samples, at most the cap.
inline int first_batch(const AntialiasingSettings& aa) {
  return aa.adaptive ? std::min(aa.min_samples, aa.max_samples) : aa.max_samples;
}

/// How far (in adaptive_threshold units) a pixel must stand above or below all of its neighbours,
/// in some display channel, to be looked at again.
inline constexpr float kOutlierThresholds = 3.0f;

/// Whether a pixel that stopped below the cap is looked at again with more samples
/// (render/integrator/image_tile_integrator.h): its display value lies more than
/// kOutlierThresholds * threshold above every neighbour's, or below every neighbour's, in some
/// channel; `highest` and `lowest` are the neighbours' largest and smallest linear values per
/// channel (the display transform is monotonic: beyond the extreme one is beyond them all).
/// Why: the first batch's pair difference sees only what differs between the two halves of the
/// pixel its samples fall in (a net puts the two samples of a pair in opposite quadrants: an
/// antithetic pair), so it is blind to a ridge or valley of the image centred in the pixel (a
/// check 2-4 pixels tall: both samples on its flanks agree while the filter-weighted mean over
/// the pixel does not), and one pair is one degree of freedom (agreement by chance). Such a pixel
/// shows as a speck, the same in every frame. The reconstruction filter (radius >= 1.5 pixels
/// but for the box) overlaps the neighbours' supports, so a band-limited image seldom has a
/// pixel beyond all eight neighbours; each neighbour's own error is at most the threshold, so
/// 3 thresholds apart from all eight is no chance. Cost: the few hundred such pixels per frame.
/// Where the pixel really is a peak (a glint smaller than a pixel) the looks go on to the cap.
inline bool stands_out(const Rgb& centre, const Rgb& highest, const Rgb& lowest,
                       const AntialiasingSettings& aa) {
  const float margin = kOutlierThresholds * aa.threshold;
  const auto beyond = [&](float c, float hi, float lo) {
    if (!(c > hi) && !(c < lo)) return false;  // not an extremum: no display value needed
    const float d = display_value(c, aa.exposure_scale);
    return d > display_value(hi, aa.exposure_scale) + margin ||
           d < display_value(lo, aa.exposure_scale) - margin;
  };
  return beyond(centre.r, highest.r, lowest.r) || beyond(centre.g, highest.g, lowest.g) ||
         beyond(centre.b, highest.b, lowest.b);
}

/// The settings of another look at a pixel whose estimate holds `samples` samples: a first batch
/// of twice as many, at most the cap (the same samples first, so the result is what the pixel
/// would have had had its error said it varies after `samples`).
inline AntialiasingSettings doubled_first_batch(const AntialiasingSettings& aa, int samples) {
  AntialiasingSettings more = aa;
  more.min_samples = std::min(2 * samples, aa.max_samples);
  return more;
}

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
  int batch_end = first_batch(aa);
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
