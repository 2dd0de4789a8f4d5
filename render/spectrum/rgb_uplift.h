#pragma once
// RGB -> spectrum uplifting (Smits 1999, "An RGB-to-spectrum conversion for reflectances",
// Journal of Graphics Tools 4(4)). A linear-sRGB reflectance is written as white plus one
// secondary (cyan, magenta or yellow) plus one primary (red, green or blue) basis spectrum with
// non-negative weights, Smits' six cases. The basis spectra (smits_basis.cpp) were re-fitted
// with Smits' own criterion for thaw's chain (CIE 1931 + D65 + IEC sRGB matrix), so:
//   reflectance rgb in [0,1]^3, lit by white light (D65, Y = 1), integrated with the CIE
//   functions and converted to sRGB, gives back rgb (exact for the basis colours; within 6e-4,
//   the IEC matrix's rounding of the D65 white, in general; tested at 1/255).
// The spectra stay within [0, 1] for rgb in [0, 1]^3, so reflectances conserve energy.
// Light colours: RGB illuminant = max(rgb) * uplift(rgb / max(rgb)) * D65 with unit luminance,
// so a light (1, 1, 1) is exactly D65 and renders white.
// Products of two non-grey RGB colours (a red light on a green wall) are not preserved by any
// uplifting: RGB and spectral rendering legitimately differ there (docs/dispersion.md).
#include <array>
#include <cstdint>

#include "render/spectrum/colour.h"
#include "render/spectrum/sampled_spectrum.h"
#include "render/spectrum/sampled_wavelengths.h"

namespace thaw::render {

namespace smits {
inline constexpr int kBins = 40;              // 10 nm bins over 380-780 nm
inline constexpr double kBinStartNm = 380.0;  // [nm]
inline constexpr double kBinWidthNm = 10.0;   // [nm]
extern const std::array<double, kBins> kWhite;
extern const std::array<double, kBins> kCyan;
extern const std::array<double, kBins> kMagenta;
extern const std::array<double, kBins> kYellow;
extern const std::array<double, kBins> kRed;
extern const std::array<double, kBins> kGreen;
extern const std::array<double, kBins> kBlue;
}  // namespace smits

/// A reflectance spectrum uplifted from linear sRGB: three weighted basis spectra.
/// Cheap to build (at shading time) and to evaluate (three table reads per wavelength).
class RgbReflectanceSpectrum {
 public:
  /// rgb components are clamped to [0, 1] (a reflectance cannot exceed 1 or be negative).
  explicit RgbReflectanceSpectrum(const LinearSrgb& rgb);

  /// Reflectance at lambda [nm] (dimensionless, in [0, 1]); 0 outside [380, 780] nm.
  double operator()(double lambda_nm) const;
  SampledSpectrum sample(const SampledWavelengths& wavelengths) const;

 private:
  double m_white = 0, m_secondary = 0, m_primary = 0;
  const std::array<double, smits::kBins>* m_secondary_basis = &smits::kCyan;
  const std::array<double, smits::kBins>* m_primary_basis = &smits::kRed;
};

/// An emission spectrum from a linear-sRGB light colour (components >= 0, any magnitude):
/// scale * uplift(rgb / scale) * D65 (unit luminance), scale = max component.
class RgbIlluminantSpectrum {
 public:
  explicit RgbIlluminantSpectrum(const LinearSrgb& rgb);

  /// Spectral radiance at lambda [nm], in units where white (1, 1, 1) has luminance Y = 1.
  double operator()(double lambda_nm) const;
  SampledSpectrum sample(const SampledWavelengths& wavelengths) const;

 private:
  double m_scale = 0;
  RgbReflectanceSpectrum m_shape;
};

}  // namespace thaw::render
