#pragma once
// Bulk absorption of a medium (Beer-Lambert): a Napierian coefficient alpha(lambda) [1/m], so
// light travelling d metres inside keeps T = exp(-alpha d) of its radiance, per wavelength.
// Constant or tabulated (linear interpolation), times an optional artistic `absorption_scale`
// (physical water and ice absorb only ~1e-2/m in the blue: a visible tint at centimetre scale
// is a deliberate choice, see docs/dispersion.md). Evaluation never throws; validate() at load.
#include <string>
#include <vector>

#include "render/spectrum/colour.h"
#include "render/spectrum/sampled_spectrum.h"
#include "render/spectrum/sampled_wavelengths.h"

namespace thaw::render::media {

class Absorption {
 public:
  /// No absorption.
  Absorption() = default;
  static Absorption constant(double per_m);
  /// alpha [1/m] at strictly increasing wavelengths [nm]; linear interpolation.
  static Absorption table(std::vector<double> wavelength_nm, std::vector<double> per_m);

  /// The same absorption multiplied by `scale` (>= 0).
  Absorption scaled(double scale) const;

  /// True when alpha is zero everywhere (the integrator can skip the exp()).
  bool is_zero() const;
  double scale() const { return m_scale; }
  bool is_table() const { return !m_table_nm.empty(); }

  /// alpha(lambda) [1/m], scale included. Tables are clamped to their end values outside their
  /// range (validate() guarantees they cover 380-780 nm).
  double per_m_at(double lambda_nm) const;
  SampledSpectrum per_m(const SampledWavelengths& wavelengths) const;
  /// exp(-alpha(l_i) * distance) for each carried wavelength; distance [m] >= 0.
  SampledSpectrum transmittance(double distance_m, const SampledWavelengths& wavelengths) const;

  /// The RGB renderer's coefficients [1/m] per linear-sRGB channel: alpha(lambda) weighted by
  /// what white light (D65, the uplift of RGB white) contributes to that channel,
  ///   alpha_c = [M int D65 cmf alpha dl]_c / [M int D65 cmf dl]_c   (M: XYZ -> linear sRGB),
  /// the slope at d = 0 of the channel's transmittance -ln T_c(d) / d of white light through d
  /// metres. Exact to first order in alpha d; the second-order error of T_c is at most
  /// var_c(alpha) d^2 / 2 (Jensen: exp of the mean is below the mean of exp, so thick media come
  /// out slightly too dark in RGB; spectral rendering is exact). Negative sRGB lobes are kept
  /// (they are what M says); a result below zero is clamped to 0.
  LinearSrgb srgb_per_m() const;

  /// Throws thaw::UserError naming `where` (e.g. "media.ice") and the key when a coefficient is
  /// negative or not finite, the table does not cover 380-780 nm or is not increasing, or the
  /// scale is negative.
  void validate(const std::string& file, const std::string& where) const;

 private:
  double m_constant_per_m = 0;
  std::vector<double> m_table_nm, m_table_per_m;
  double m_scale = 1;
};

}  // namespace thaw::render::media
