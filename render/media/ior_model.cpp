// Index-of-refraction models; see ior_model.h.
#include "render/media/ior_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "base/error.h"
#include "render/media/wavelength_table.h"

namespace thaw::render::media {
namespace {

std::string num(double v) {
  return table_number(v);
}

/// Linear interpolation in a strictly increasing table, clamped at the ends.
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  if (at <= x.front()) return y.front();
  if (at >= x.back()) return y.back();
  const auto it = std::upper_bound(x.begin(), x.end(), at);
  const auto i = static_cast<std::size_t>(it - x.begin()) - 1;
  const double t = (at - x[i]) / (x[i + 1] - x[i]);
  return y[i] * (1 - t) + y[i + 1] * t;
}

}  // namespace

IorModel IorModel::constant(double n) {
  IorModel m;
  m.m_kind = Kind::constant;
  m.m_constant = n;
  return m;
}

IorModel IorModel::sellmeier(std::vector<double> b, std::vector<double> c_um2) {
  IorModel m;
  m.m_kind = Kind::sellmeier;
  m.m_b = std::move(b);
  m.m_c = std::move(c_um2);
  return m;
}

IorModel IorModel::sellmeier_gas(std::vector<double> b, std::vector<double> c_um2) {
  IorModel m = sellmeier(std::move(b), std::move(c_um2));
  m.m_kind = Kind::sellmeier_gas;
  return m;
}

IorModel IorModel::cauchy(double a, double b_um2, double c_um4) {
  IorModel m;
  m.m_kind = Kind::cauchy;
  m.m_b = {a, b_um2, c_um4};
  return m;
}

IorModel IorModel::table(std::vector<double> wavelength_nm, std::vector<double> n) {
  IorModel m;
  m.m_kind = Kind::table;
  m.m_table_nm = std::move(wavelength_nm);
  m.m_table_n = std::move(n);
  return m;
}

IorModel IorModel::iapws97(double temperature_c, double density_kg_m3) {
  IorModel m;
  m.m_kind = Kind::iapws97;
  m.m_temperature_c = temperature_c;
  m.m_density_kg_m3 = density_kg_m3;
  return m;
}

std::string IorModel::kind_name() const {
  switch (m_kind) {
    case Kind::constant:
      return "constant";
    case Kind::sellmeier:
      return "sellmeier";
    case Kind::sellmeier_gas:
      return "sellmeier (n-1)";
    case Kind::cauchy:
      return "cauchy";
    case Kind::table:
      return "table";
    case Kind::iapws97:
      return "iapws-r9-97";
  }
  return "?";
}

double IorModel::n_at(double lambda_nm) const {
  const double l_um = lambda_nm * 1e-3;
  const double l2 = l_um * l_um;
  switch (m_kind) {
    case Kind::constant:
      return m_constant;
    case Kind::sellmeier:
    case Kind::sellmeier_gas: {
      double s = 0;
      for (std::size_t i = 0; i < m_b.size(); ++i) s += m_b[i] * l2 / (l2 - m_c[i]);
      if (m_kind == Kind::sellmeier_gas) return 1 + s;
      return std::sqrt(1 + s);
    }
    case Kind::cauchy:
      return m_b[0] + m_b[1] / l2 + m_b[2] / (l2 * l2);
    case Kind::table:
      return interpolate(m_table_nm, m_table_n, lambda_nm);
    case Kind::iapws97: {
      // IAPWS R9-97 eq. (1): (n^2 - 1)/(n^2 + 2) / rho_bar = a0 + a1 rho_bar + a2 T_bar
      //   + a3 l_bar^2 T_bar + a4 / l_bar^2 + a5 / (l_bar^2 - l_UV^2) + a6 / (l_bar^2 - l_IR^2)
      //   + a7 rho_bar^2, with T* = 273.15 K, rho* = 1000 kg/m^3, l* = 0.589 um.
      constexpr double a0 = 0.244257733, a1 = 0.974634476e-2, a2 = -0.373234996e-2,
                       a3 = 0.268678472e-3, a4 = 0.158920570e-2, a5 = 0.245934259e-2,
                       a6 = 0.900704920, a7 = -0.166626219e-1;
      constexpr double l_uv = 0.2292020, l_ir = 5.432937;
      const double t = (m_temperature_c + 273.15) / 273.15;
      const double rho = m_density_kg_m3 / 1000.0;
      const double l = l_um / 0.589;
      const double lb2 = l * l;
      const double a = rho * (a0 + a1 * rho + a2 * t + a3 * lb2 * t + a4 / lb2 +
                              a5 / (lb2 - l_uv * l_uv) + a6 / (lb2 - l_ir * l_ir) + a7 * rho * rho);
      return std::sqrt((1 + 2 * a) / (1 - a));
    }
  }
  return 1;
}

SampledSpectrum IorModel::n(const SampledWavelengths& wavelengths) const {
  SampledSpectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i)
    s[i] = static_cast<float>(n_at(wavelengths.lambda_nm(i)));
  return s;
}

double IorModel::abbe_number() const {
  if (!is_dispersive()) return std::numeric_limits<double>::infinity();
  return (n_at(kFraunhoferD_nm) - 1) / (n_at(kFraunhoferF_nm) - n_at(kFraunhoferC_nm));
}

void IorModel::validate(const std::string& file, const std::string& where) const {
  auto fail = [&](const std::string& key, const std::string& problem) {
    throw UserError(file, "key '" + where + (key.empty() ? "" : "." + key) + "'", problem);
  };
  const std::string range =
      "the rendered range " + num(kLambdaMinNm) + "-" + num(kLambdaMaxNm) + " nm";
  switch (m_kind) {
    case Kind::constant:
      if (!std::isfinite(m_constant) || m_constant < 1)
        fail("ior",
             "index of refraction must be a finite number >= 1 (got " + num(m_constant) + ")");
      return;
    case Kind::sellmeier:
    case Kind::sellmeier_gas: {
      if (m_b.empty()) fail("sellmeier.B", "needs at least one term");
      if (m_b.size() != m_c.size())
        fail("sellmeier", "B has " + std::to_string(m_b.size()) + " terms but C has " +
                              std::to_string(m_c.size()));
      for (std::size_t i = 0; i < m_c.size(); ++i) {
        const std::string key = "sellmeier.C[" + std::to_string(i) + "]";
        if (!std::isfinite(m_b[i]) || !std::isfinite(m_c[i])) fail(key, "must be finite");
        if (m_c[i] < 0)
          fail(key,
               "must not be negative (C is a squared wavelength, um^2; got " + num(m_c[i]) + ")");
        const double pole_nm = std::sqrt(m_c[i]) * 1e3;
        if (pole_nm >= kLambdaMinNm && pole_nm <= kLambdaMaxNm)
          fail(key, "pole at sqrt(C) = " + num(pole_nm) + " nm lies inside " + range +
                        " (C is in um^2: did you give nm^2 or um?)");
      }
      break;
    }
    case Kind::cauchy:
      for (double v : m_b)
        if (!std::isfinite(v)) fail("cauchy", "coefficients must be finite");
      break;
    case Kind::table: {
      const auto table =
          wavelength_table_problem(m_table_nm, m_table_n, {"n", 1.0, "a finite number >= 1"});
      if (table) fail("table" + (table->key.empty() ? "" : "." + table->key), table->problem);
      return;
    }
    case Kind::iapws97:
      // Range of validity of R9-97: -12 to 500 deg C, 0 to 1060 kg/m^3, 0.2 to 1.1 um.
      if (!(m_temperature_c >= -12 && m_temperature_c <= 500))
        fail("iapws.temperature_c",
             "must be within the formulation's -12..500 deg C (got " + num(m_temperature_c) + ")");
      if (!(m_density_kg_m3 > 0 && m_density_kg_m3 <= 1060))
        fail("iapws.density_kg_m3",
             "must be within the formulation's 0..1060 kg/m^3 (got " + num(m_density_kg_m3) + ")");
      break;
  }
  // Analytic models: n must be finite and >= 1 everywhere in the range (1 nm steps, plus the
  // ends); catches negative n^2 and poles just outside the range that still blow up inside.
  for (double l = kLambdaMinNm; l <= kLambdaMaxNm; l += 1.0) {
    const double n = n_at(l);
    if (!std::isfinite(n) || n < 1)
      fail(
          kind_name() == "cauchy"   ? "cauchy"
          : m_kind == Kind::iapws97 ? "iapws"
                                    : "sellmeier",
          "gives n = " + num(n) + " at " + num(l) + " nm; n must be finite and >= 1 over " + range);
  }
}

}  // namespace thaw::render::media
