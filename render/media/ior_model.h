#pragma once
// Index of refraction n(lambda) of one medium, relative to vacuum, over the rendered range
// 380-780 nm. Models: constant; Sellmeier n^2 = 1 + sum B_i l^2 / (l^2 - C_i) (l in um, C_i in
// um^2; Sellmeier 1871, the form of glass catalogues); its gas form n - 1 = sum B_i l^2 /
// (l^2 - C_i) (Ciddor 1996 writes standard air this way); Cauchy n = A + B/l^2 + C/l^4 (l in um);
// a table n(l) with linear interpolation; and the IAPWS R9-97 formulation for liquid water at a
// temperature and density. Validation (validate()) runs once at load time; evaluation never
// throws (it runs inside the render loop). Knows nothing about TOML or scenes.
#include <string>
#include <vector>

#include "render/spectrum/sampled_spectrum.h"
#include "render/spectrum/sampled_wavelengths.h"

namespace thaw::render::media {

/// Fraunhofer lines for dispersion figures [nm] (Schott's definitions).
inline constexpr double kFraunhoferD_nm = 587.5618;  // helium d line
inline constexpr double kFraunhoferF_nm = 486.1327;  // hydrogen F line
inline constexpr double kFraunhoferC_nm = 656.2725;  // hydrogen C line

class IorModel {
 public:
  enum class Kind { constant, sellmeier, sellmeier_gas, cauchy, table, iapws97 };

  static IorModel constant(double n);
  /// B dimensionless, C [um^2]; same length, at least one term.
  static IorModel sellmeier(std::vector<double> b, std::vector<double> c_um2);
  /// Gas form n - 1 = sum B_i l^2 / (l^2 - C_i).
  static IorModel sellmeier_gas(std::vector<double> b, std::vector<double> c_um2);
  /// n = A + B / l^2 + C / l^4, B [um^2], C [um^4].
  static IorModel cauchy(double a, double b_um2, double c_um4);
  /// Tabulated n at strictly increasing wavelengths [nm]; linear interpolation.
  static IorModel table(std::vector<double> wavelength_nm, std::vector<double> n);
  /// IAPWS R9-97 (Release on the refractive index of ordinary water substance as a function of
  /// wavelength, temperature and pressure, 1997): temperature [deg C], density [kg/m^3].
  static IorModel iapws97(double temperature_c, double density_kg_m3);

  Kind kind() const { return m_kind; }
  /// "constant", "sellmeier", ... (for listings).
  std::string kind_name() const;
  /// False only for a constant index: refraction then sends every wavelength the same way and
  /// the integrator keeps all of them (no terminate_secondary()).
  bool is_dispersive() const { return m_kind != Kind::constant; }

  /// n at lambda [nm]. Inside [380, 780] nm after a successful validate(); tables are clamped
  /// to their end values outside their range (never reached for a validated model).
  double n_at(double lambda_nm) const;
  SampledSpectrum n(const SampledWavelengths& wavelengths) const;

  /// Abbe number V_d = (n_d - 1) / (n_F - n_C); infinite for a constant index.
  double abbe_number() const;

  /// Throws thaw::UserError(file, where + ".<key>", problem) when the model is unusable over
  /// 380-780 nm: a Sellmeier pole sqrt(C_i) inside the range, a table not covering it or not
  /// increasing, any n < 1 or non-finite n in the range, mismatched coefficient lists.
  /// `where` names the medium's key path, e.g. "media.glass".
  void validate(const std::string& file, const std::string& where) const;

  // Parameters, for listings and tests.
  const std::vector<double>& coefficients_b() const { return m_b; }
  const std::vector<double>& coefficients_c() const { return m_c; }
  const std::vector<double>& table_wavelengths_nm() const { return m_table_nm; }
  const std::vector<double>& table_n() const { return m_table_n; }

 private:
  Kind m_kind = Kind::constant;
  double m_constant = 1;
  std::vector<double> m_b, m_c;  // Sellmeier B_i, C_i; Cauchy {A, B, C} in m_b
  std::vector<double> m_table_nm, m_table_n;
  double m_temperature_c = 0, m_density_kg_m3 = 0;
};

}  // namespace thaw::render::media
