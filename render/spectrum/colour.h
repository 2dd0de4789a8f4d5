#pragma once
// Colour science for the spectral film: CIE 1931 2-degree colour-matching functions, the D65
// illuminant, XYZ <-> linear sRGB (IEC 61966-2-1), and the Monte-Carlo estimator that turns the
// radiance carried at a few sampled wavelengths into XYZ. Units: wavelengths in nm, spectral
// radiance in the renderer's relative units per nm. Knows nothing about scenes or images.
#include "render/spectrum/sampled_spectrum.h"
#include "render/spectrum/sampled_wavelengths.h"

namespace thaw::render {

/// CIE XYZ tristimulus values.
struct Xyz {
  double x = 0, y = 0, z = 0;
};

/// Linear (not gamma-encoded) sRGB, D65 white.
struct LinearSrgb {
  double r = 0, g = 0, b = 0;
};

/// CIE 1931 2-degree colour-matching functions at lambda [nm], linearly interpolated in the
/// 5 nm CIE table; zero outside [380, 780] nm.
Xyz cie_xyz_bar(double lambda_nm);

/// CIE D65 relative spectral power at lambda [nm] (100 at 560 nm), linear interpolation; zero
/// outside [380, 780] nm.
double cie_d65(double lambda_nm);

/// D65 scaled so that its luminance integral over 380-780 nm is 1: "white light" (1, 1, 1).
/// Its XYZ is (0.9505, 1, 1.0888), which sRGB maps to (1, 1, 1) within 2e-4.
double illuminant_d65(double lambda_nm);
SampledSpectrum illuminant_d65(const SampledWavelengths& wavelengths);

/// XYZ -> linear sRGB with the IEC 61966-2-1 matrix (4-decimal form, as published).
LinearSrgb xyz_to_linear_srgb(const Xyz& xyz);
/// linear sRGB -> XYZ (the standard's inverse matrix).
Xyz linear_srgb_to_xyz(const LinearSrgb& rgb);

/// Chromaticity (x, y) = (X, Y) / (X + Y + Z).
struct Chromaticity {
  double x = 0, y = 0;
};
Chromaticity chromaticity(const Xyz& xyz);

/// The film estimator: XYZ of the spectral radiance `radiance` carried at `wavelengths`,
/// XYZ ~= (1/N) sum_i L(l_i) cmf(l_i) / pdf(l_i). Unbiased for the integral
/// XYZ = integral over 380-780 nm of L(l) cmf(l) dl (tested statistically). Wavelengths whose
/// pdf is 0 (terminated secondaries) contribute nothing.
Xyz spectrum_to_xyz(const SampledSpectrum& radiance, const SampledWavelengths& wavelengths);

/// Convenience: spectrum_to_xyz followed by xyz_to_linear_srgb.
LinearSrgb spectrum_to_linear_srgb(const SampledSpectrum& radiance,
                                   const SampledWavelengths& wavelengths);

}  // namespace thaw::render
