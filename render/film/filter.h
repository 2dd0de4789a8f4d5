#pragma once
// Pixel reconstruction filters, used by filter importance sampling (Ernst et al. 2006, "Filter
// Importance Sampling"; pbrt-v4 sec. 8.8): each camera sample's offset from the pixel centre is
// drawn with density proportional to |f|, and carries the weight f / (pdf * integral of f), whose
// expectation is exactly 1, so a pixel is the plain mean of weight * radiance. Every sample
// belongs to one pixel: no splatting across pixels or tiles, hence no dependence on tile order.
//   box       f = 1 on [-r, r]^2 (r = 0.5: today's images)
//   gaussian  f(x) = exp(-x^2 / (2 s^2)) - exp(-r^2 / (2 s^2)), s = r / 3, separable
//   mitchell  Mitchell & Netravali 1988 with B = C = 1/3 on [-r, r], separable (negative lobes)
// Knows nothing about images or cameras.
#include <optional>
#include <string_view>
#include <vector>

#include "render/sampling/pixel_sampler.h"

namespace thaw::render {

enum class FilterKind { box, gaussian, mitchell };

/// "box" | "gaussian" | "mitchell"; nullopt for anything else (the parser's one rule).
std::optional<FilterKind> filter_kind_from_name(std::string_view name);
const char* filter_name(FilterKind kind);
/// The radius a filter has when the scene gives none [pixels]: box 0.5, gaussian 1.5, mitchell 2.
double default_filter_radius(FilterKind kind);
/// Accepted radii [pixels]: a box below half a pixel would leave gaps, beyond 4 it is only blur.
inline constexpr double kMinFilterRadius = 0.5, kMaxFilterRadius = 4.0;

struct FilterSample {
  /// offset from the pixel centre [pixels]
  float dx = 0, dy = 0;
  /// f / (pdf * integral of f); expectation 1
  float weight = 1;
};

class Filter {
 public:
  Filter(FilterKind kind, double radius);
  FilterKind kind() const { return m_kind; }
  float radius() const { return m_radius; }
  /// f(x, y) = f1(x) f1(y), unnormalised.
  float evaluate(float x, float y) const { return evaluate_1d(x) * evaluate_1d(y); }
  float evaluate_1d(float x) const;
  /// The truncated Gaussian's f1(x) from its formula (evaluate_1d reads a table of it).
  double gaussian_1d(double x) const;
  /// A sample offset from the unit-square point `u`.
  FilterSample sample(sampling::Point2 u) const;

 private:
  /// Offset in [-r, r] drawn from the tabulated |f1|, and f1 / pdf at it.
  float sample_1d(float u, float& ratio) const;

  FilterKind m_kind;
  float m_radius;
  /// piecewise-constant |f1| over kBins equal bins of [-r, r], its CDF (cdf[0] = 0, cdf[n] = 1),
  /// and integral of f1 / integral of the tabulated |f1|: weight = sign * ... / this.
  std::vector<float> m_abs, m_cdf;
  /// per bin: 1 / (cdf[i + 1] - cdf[i]) and 1 / pdf, 0 where those are 0
  std::vector<float> m_inv_bin_mass, m_inv_pdf;
  /// m_guide[g] = the first i with m_cdf[i] > g / kGuideCells: where the search for a u in
  /// [g, g + 1) / kGuideCells starts (a guide table, Devroye 1986 sec. III.2.4; the result is
  /// std::upper_bound's, found by a short forward scan instead of eight unpredictable branches)
  static constexpr int kGuideCells = 256;
  std::vector<int> m_guide;
  float m_abs_integral = 0, m_signed_integral = 0;
  /// gaussian: exp(-r^2 / (2 s^2)), the value subtracted so that f1(r) = 0
  double m_gaussian_floor = 0;
  /// gaussian: f1 at kGaussianNodes + 1 even steps of [0, r], the last repeated
  static constexpr int kGaussianNodes = 1024;
  std::vector<float> m_gaussian_table;
};

}  // namespace thaw::render
