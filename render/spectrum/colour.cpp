// Colour-matching, D65 and sRGB conversions; see colour.h. Tables: render/spectrum/cie_tables.cpp.
#include "render/spectrum/colour.h"

#include <algorithm>
#include <cmath>

#include "render/spectrum/cie_tables.h"

namespace thaw::render {
namespace {

/// Linear interpolation in a 5 nm CIE table; 0 outside it.
double lookup(const std::array<double, cie::kTableSize>& table, double lambda_nm) {
  const double x = (lambda_nm - cie::kTableStartNm) / cie::kTableStepNm;
  if (!(x >= 0) || x > static_cast<double>(cie::kTableSize - 1)) return 0;
  const auto i = std::min(static_cast<std::size_t>(x), cie::kTableSize - 2);
  const double t = x - static_cast<double>(i);
  return table[i] * (1 - t) + table[i + 1] * t;
}

/// Integral of piecewise-linear D65 times piecewise-linear y-bar over the tables' range:
/// on each 5 nm interval the product is quadratic, so Simpson's rule is exact.
double d65_luminance_integral() {
  double sum = 0;
  for (std::size_t i = 0; i + 1 < cie::kTableSize; ++i) {
    const double a = cie::kD65[i] * cie::kYBar[i];
    const double b = cie::kD65[i + 1] * cie::kYBar[i + 1];
    const double m = 0.25 * (cie::kD65[i] + cie::kD65[i + 1]) * (cie::kYBar[i] + cie::kYBar[i + 1]);
    sum += cie::kTableStepNm / 6.0 * (a + 4 * m + b);
  }
  return sum;
}

const double kD65Scale = 1.0 / d65_luminance_integral();

}  // namespace

Xyz cie_xyz_bar(double lambda_nm) {
  return {lookup(cie::kXBar, lambda_nm), lookup(cie::kYBar, lambda_nm),
          lookup(cie::kZBar, lambda_nm)};
}

double cie_d65(double lambda_nm) {
  return lookup(cie::kD65, lambda_nm);
}

double illuminant_d65(double lambda_nm) {
  return kD65Scale * cie_d65(lambda_nm);
}

SampledSpectrum illuminant_d65(const SampledWavelengths& wavelengths) {
  SampledSpectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i)
    s[i] = static_cast<float>(illuminant_d65(wavelengths.lambda_nm(i)));
  return s;
}

// IEC 61966-2-1:1999 (sRGB), section 5.2, the matrix as published to 4 decimals.
LinearSrgb xyz_to_linear_srgb(const Xyz& c) {
  return {3.2406 * c.x - 1.5372 * c.y - 0.4986 * c.z, -0.9689 * c.x + 1.8758 * c.y + 0.0415 * c.z,
          0.0557 * c.x - 0.2040 * c.y + 1.0570 * c.z};
}

// IEC 61966-2-1:1999 section 5.3 (inverse direction).
Xyz linear_srgb_to_xyz(const LinearSrgb& c) {
  return {0.4124 * c.r + 0.3576 * c.g + 0.1805 * c.b, 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b,
          0.0193 * c.r + 0.1192 * c.g + 0.9505 * c.b};
}

Chromaticity chromaticity(const Xyz& c) {
  const double s = c.x + c.y + c.z;
  if (!(s != 0)) return {0, 0};
  return {c.x / s, c.y / s};
}

Xyz spectrum_to_xyz(const SampledSpectrum& radiance, const SampledWavelengths& wavelengths) {
  Xyz out;
  for (int i = 0; i < kSpectrumSamples; ++i) {
    const double pdf = wavelengths.pdf(i);
    if (pdf == 0) continue;
    const Xyz bar = cie_xyz_bar(wavelengths.lambda_nm(i));
    const double w = radiance[i] / pdf;
    out.x += w * bar.x;
    out.y += w * bar.y;
    out.z += w * bar.z;
  }
  out.x /= kSpectrumSamples;
  out.y /= kSpectrumSamples;
  out.z /= kSpectrumSamples;
  return out;
}

LinearSrgb spectrum_to_linear_srgb(const SampledSpectrum& radiance,
                                   const SampledWavelengths& wavelengths) {
  return xyz_to_linear_srgb(spectrum_to_xyz(radiance, wavelengths));
}

}  // namespace thaw::render
