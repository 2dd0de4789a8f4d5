// Smits (1999) uplifting; see rgb_uplift.h. The case analysis follows the paper's pseudo-code:
// the smallest component is white, the middle one minus the smallest is the secondary made of
// the two largest primaries, the largest minus the middle is the largest primary.
#include "render/spectrum/rgb_uplift.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace thaw::render {
namespace {

double clamp01(double v) {
  return std::isnan(v) ? 0.0 : std::clamp(v, 0.0, 1.0);
}

int bin_of(double lambda_nm) {
  const double x = (lambda_nm - smits::kBinStartNm) / smits::kBinWidthNm;
  if (!(x >= 0) || x > smits::kBins) return -1;
  return std::min(static_cast<int>(x), smits::kBins - 1);
}

}  // namespace

RgbReflectanceSpectrum::RgbReflectanceSpectrum(const LinearSrgb& in) {
  const double r = clamp01(in.r), g = clamp01(in.g), b = clamp01(in.b);
  if (r <= g && r <= b) {  // red smallest: white + cyan (g, b) + green or blue
    m_white = r;
    if (g <= b) {
      m_secondary = g - r;
      m_primary = b - g;
      m_primary_basis = &smits::kBlue;
    } else {
      m_secondary = b - r;
      m_primary = g - b;
      m_primary_basis = &smits::kGreen;
    }
    m_secondary_basis = &smits::kCyan;
  } else if (g <= r && g <= b) {  // green smallest: white + magenta (r, b) + red or blue
    m_white = g;
    if (r <= b) {
      m_secondary = r - g;
      m_primary = b - r;
      m_primary_basis = &smits::kBlue;
    } else {
      m_secondary = b - g;
      m_primary = r - b;
      m_primary_basis = &smits::kRed;
    }
    m_secondary_basis = &smits::kMagenta;
  } else {  // blue smallest: white + yellow (r, g) + red or green
    m_white = b;
    if (r <= g) {
      m_secondary = r - b;
      m_primary = g - r;
      m_primary_basis = &smits::kGreen;
    } else {
      m_secondary = g - b;
      m_primary = r - g;
      m_primary_basis = &smits::kRed;
    }
    m_secondary_basis = &smits::kYellow;
  }
}

double RgbReflectanceSpectrum::operator()(double lambda_nm) const {
  const int i = bin_of(lambda_nm);
  if (i < 0) return 0;
  const auto k = static_cast<std::size_t>(i);
  // The three weights sum to the largest component (<= 1) and each basis is in [0, 1].
  return m_white + m_secondary * (*m_secondary_basis)[k] + m_primary * (*m_primary_basis)[k];
}

SampledSpectrum RgbReflectanceSpectrum::sample(const SampledWavelengths& wavelengths) const {
  SampledSpectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i)
    s[i] = static_cast<float>((*this)(wavelengths.lambda_nm(i)));
  return s;
}

RgbIlluminantSpectrum::RgbIlluminantSpectrum(const LinearSrgb& rgb)
    : m_scale(std::max({rgb.r, rgb.g, rgb.b, 0.0})),
      m_shape(m_scale > 0 ? LinearSrgb{rgb.r / m_scale, rgb.g / m_scale, rgb.b / m_scale}
                          : LinearSrgb{}) {}

double RgbIlluminantSpectrum::operator()(double lambda_nm) const {
  if (m_scale == 0) return 0;
  return m_scale * m_shape(lambda_nm) * illuminant_d65(lambda_nm);
}

SampledSpectrum RgbIlluminantSpectrum::sample(const SampledWavelengths& wavelengths) const {
  SampledSpectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i)
    s[i] = static_cast<float>((*this)(wavelengths.lambda_nm(i)));
  return s;
}

}  // namespace thaw::render
