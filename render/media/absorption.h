#pragma once
// Bulk absorption of a medium (Beer-Lambert): a Napierian coefficient alpha(lambda) [1/m], so
// light travelling d metres inside keeps T = exp(-alpha d) of its radiance, per wavelength.
// Constant or tabulated (linear interpolation), times an optional artistic `absorption_scale`
// (physical water and ice absorb only ~1e-2/m in the blue: a visible tint at centimetre scale
// is a deliberate choice, see docs/dispersion.md). Evaluation never throws; validate() at load.
#include <string>
#include <vector>

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
