#include "sim/boundary/air_model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

// GCC 12 reports a false -Wrestrict inside std::string's operator+(const char*, string&&) once
// these messages are inlined into one function (GCC bug 105651, fixed in GCC 13).
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ == 12
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

namespace thaw::sim {

namespace {

constexpr double kKelvin = 273.15;
constexpr double kGravity = 9.80665;                 // standard gravity [m/s^2]
constexpr double kStefanBoltzmann = 5.670374419e-8;  // CODATA 2018 [W/(m^2 K^4)]
constexpr double kAtmosphere = 101325.0;             // [Pa]
constexpr double kGasConstantAir = 287.05;           // dry air [J/(kg K)]
constexpr double kGasConstantVapour = 461.52;        // water vapour, R / M_w [J/(kg K)]
constexpr double kSpecificHeatAir = 1006.0;          // Incropera Table A.4, 250-300 K [J/(kg K)]

// The validity limits (docs/simulate.md cites each with its source).
constexpr double kMagnusLowC = -40.0, kMagnusHighC = 50.0;
constexpr double kSphereNaturalMaxRa = 1e11;
constexpr double kWhitakerMinRe = 3.5, kWhitakerMaxRe = 7.6e4;
constexpr double kWhitakerMinViscosityRatio = 1.0, kWhitakerMaxViscosityRatio = 3.2;
constexpr double kChurchillChuMaxRa = 1e12;
constexpr double kChurchillBernsteinMinRePr = 0.2;
constexpr double kPlateMaxRe = 5e5, kPlateMinRePr = 100.0;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

double sutherland(double t_k, double ref_value, double ref_t_k, double s_k) {
  return ref_value * std::pow(t_k / ref_t_k, 1.5) * (ref_t_k + s_k) / (t_k + s_k);
}

double viscosity(double t_c) {
  return sutherland(t_c + kKelvin, 1.716e-5, 273.0, 111.0);  // White Table 1-2
}

double vapour_density(double pressure_pa, double t_c) {
  return pressure_pa / (kGasConstantVapour * (t_c + kKelvin));
}

double rayleigh(const AirProperties& p, double delta_t, double length_m) {
  return kGravity * p.expansion_coefficient_per_k * std::abs(delta_t) * length_m * length_m *
         length_m / (p.kinematic_viscosity_m2_s * p.thermal_diffusivity_m2_s);
}

double natural_nusselt(AirBody body, double ra, double pr) {
  switch (body) {
    case AirBody::sphere:
      return nusselt_sphere_natural(ra, pr);
    case AirBody::horizontal_cylinder:
      return nusselt_horizontal_cylinder_natural(ra, pr);
    case AirBody::vertical_surface:
      return nusselt_vertical_natural(ra, pr);
  }
  return 0;
}

const char* body_text(AirBody body) {
  switch (body) {
    case AirBody::sphere:
      return "a sphere of D = ";
    case AirBody::horizontal_cylinder:
      return "a cylinder of D = ";
    case AirBody::vertical_surface:
      return "a vertical surface of H = ";
  }
  return "";
}

}  // namespace

const char* to_string(AirBody body) {
  switch (body) {
    case AirBody::sphere:
      return "sphere";
    case AirBody::horizontal_cylinder:
      return "horizontal_cylinder";
    case AirBody::vertical_surface:
      return "vertical_surface";
  }
  return "?";
}

AirProperties air_properties(double temperature_c) {
  AirProperties p;
  const double t_k = temperature_c + kKelvin;
  p.density_kg_m3 = kAtmosphere / (kGasConstantAir * t_k);
  p.specific_heat_j_kgk = kSpecificHeatAir;
  p.viscosity_pa_s = viscosity(temperature_c);
  p.conductivity_w_mk = sutherland(t_k, 0.0241, 273.0, 194.0);  // White Table 1-3
  p.kinematic_viscosity_m2_s = p.viscosity_pa_s / p.density_kg_m3;
  p.thermal_diffusivity_m2_s = p.conductivity_w_mk / (p.density_kg_m3 * p.specific_heat_j_kgk);
  p.prandtl = p.kinematic_viscosity_m2_s / p.thermal_diffusivity_m2_s;
  p.vapour_diffusivity_m2_s = 0.26e-4 * std::pow(t_k / 298.0, 1.5);
  p.expansion_coefficient_per_k = 1.0 / t_k;
  return p;
}

double saturation_vapour_pressure_pa(double temperature_c) {
  return 610.94 * std::exp(17.625 * temperature_c / (temperature_c + 243.04));
}

double vaporisation_heat_j_kg(double temperature_c) {
  return 2.501e6 - 2370.0 * temperature_c;
}

double nusselt_sphere_natural(double rayleigh, double prandtl) {
  return 2.0 + 0.589 * std::pow(rayleigh, 0.25) /
                   std::pow(1.0 + std::pow(0.469 / prandtl, 9.0 / 16.0), 4.0 / 9.0);
}

double nusselt_sphere_forced(double reynolds, double prandtl, double viscosity_ratio) {
  return 2.0 + (0.4 * std::sqrt(reynolds) + 0.06 * std::pow(reynolds, 2.0 / 3.0)) *
                   std::pow(prandtl, 0.4) * std::pow(viscosity_ratio, 0.25);
}

double nusselt_horizontal_cylinder_natural(double rayleigh, double prandtl) {
  const double root = 0.60 + 0.387 * std::pow(rayleigh, 1.0 / 6.0) /
                                 std::pow(1.0 + std::pow(0.559 / prandtl, 9.0 / 16.0), 8.0 / 27.0);
  return root * root;
}

double nusselt_cylinder_forced(double reynolds, double prandtl) {
  return 0.3 + 0.62 * std::sqrt(reynolds) * std::cbrt(prandtl) /
                   std::pow(1.0 + std::pow(0.4 / prandtl, 2.0 / 3.0), 0.25) *
                   std::pow(1.0 + std::pow(reynolds / 282000.0, 5.0 / 8.0), 4.0 / 5.0);
}

double nusselt_vertical_natural(double rayleigh, double prandtl) {
  const double root = 0.825 + 0.387 * std::pow(rayleigh, 1.0 / 6.0) /
                                  std::pow(1.0 + std::pow(0.492 / prandtl, 9.0 / 16.0), 8.0 / 27.0);
  return root * root;
}

double nusselt_plate_forced(double reynolds, double prandtl) {
  return 0.6774 * std::sqrt(reynolds) * std::cbrt(prandtl) /
         std::pow(1.0 + std::pow(0.0468 / prandtl, 2.0 / 3.0), 0.25);
}

double nusselt_mixed(double forced, double natural) {
  return std::cbrt(forced * forced * forced + natural * natural * natural);
}

AirFlux air_heat_flux(const Air& air, const AirBodySize& body, double surface_temperature_c) {
  AirFlux out;
  const double ts = surface_temperature_c, tinf = air.temperature_c;
  const double length = body.length_m;
  const AirProperties film = air_properties(0.5 * (ts + tinf));
  out.nusselt_natural = natural_nusselt(body.kind, rayleigh(film, tinf - ts, length), film.prandtl);
  const double h_natural = out.nusselt_natural * film.conductivity_w_mk / length;
  double h_forced = 0;
  if (air.speed_m_s > 0) {
    if (body.kind == AirBody::sphere) {
      // Whitaker 1972: properties at T_inf, the viscosity ratio mu_inf / mu_s.
      const AirProperties free = air_properties(tinf);
      const double re = air.speed_m_s * length / free.kinematic_viscosity_m2_s;
      out.nusselt_forced =
          nusselt_sphere_forced(re, free.prandtl, free.viscosity_pa_s / viscosity(ts));
      h_forced = out.nusselt_forced * free.conductivity_w_mk / length;
    } else {
      const double re = air.speed_m_s * length / film.kinematic_viscosity_m2_s;
      out.nusselt_forced = body.kind == AirBody::horizontal_cylinder
                               ? nusselt_cylinder_forced(re, film.prandtl)
                               : nusselt_plate_forced(re, film.prandtl);
      h_forced = out.nusselt_forced * film.conductivity_w_mk / length;
    }
  }
  // Mixed convection, combined on h so that each part keeps the conductivity it was fitted with.
  const double h = nusselt_mixed(h_forced, h_natural);
  out.heat_transfer_coefficient_w_m2k = h;
  out.convection_w_m2 = h * (tinf - ts);

  const double t_sur_k = air.surroundings_temperature_c + kKelvin, ts_k = ts + kKelvin;
  out.radiation_w_m2 = air.emissivity * kStefanBoltzmann *
                       (t_sur_k * t_sur_k * t_sur_k * t_sur_k - ts_k * ts_k * ts_k * ts_k);

  // Chilton-Colburn: h / h_m = rho c_p Le^(2/3) (Incropera 7th ed., eq. 6.92), Le = alpha / D_AB.
  const double lewis = film.thermal_diffusivity_m2_s / film.vapour_diffusivity_m2_s;
  out.mass_transfer_coefficient_m_s =
      h / (film.density_kg_m3 * film.specific_heat_j_kgk * std::pow(lewis, 2.0 / 3.0));
  const double rho_v_air =
      vapour_density(air.relative_humidity * saturation_vapour_pressure_pa(tinf), tinf);
  const double rho_v_surface = vapour_density(saturation_vapour_pressure_pa(ts), ts);
  out.mass_flux_kg_m2s = out.mass_transfer_coefficient_m_s * (rho_v_air - rho_v_surface);
  out.latent_w_m2 = out.mass_flux_kg_m2s * vaporisation_heat_j_kg(ts);
  return out;
}

std::optional<AirProblem> find_air_problem(const Air& air, const AirBodySize& body,
                                           double coldest_surface_c, double warmest_surface_c) {
  auto problem = [](AirInput input, std::string message) {
    return std::optional<AirProblem>(AirProblem{input, std::move(message)});
  };
  if (!std::isfinite(air.emissivity) || !(air.emissivity > 0 && air.emissivity <= 1))
    return problem(AirInput::emissivity, "(" + num(air.emissivity) + ") is outside (0, 1]");
  if (!std::isfinite(air.relative_humidity) ||
      !(air.relative_humidity >= 0 && air.relative_humidity <= 1))
    return problem(AirInput::relative_humidity,
                   "(" + num(air.relative_humidity) + ") is outside [0, 1]");
  if (!std::isfinite(air.speed_m_s) || !(air.speed_m_s >= 0))
    return problem(AirInput::speed,
                   "(" + num(air.speed_m_s) + " m/s) must be 0 (still air) or positive");
  if (!std::isfinite(air.temperature_c) ||
      !(air.temperature_c >= kMagnusLowC && air.temperature_c <= kMagnusHighC))
    return problem(
        AirInput::temperature,
        "(" + num(air.temperature_c) +
            " C) is outside [-40, 50] C, the range of the "
            "Magnus saturation vapour pressure (Alduchov & Eskridge 1996) and of the air "
            "properties used");
  if (!std::isfinite(air.surroundings_temperature_c) ||
      !(air.surroundings_temperature_c > -kKelvin && air.surroundings_temperature_c <= 1000))
    return problem(AirInput::surroundings_temperature,
                   "(" + num(air.surroundings_temperature_c) +
                       " C) is outside (-273.15, 1000] C (absolute zero to a flame)");
  if (!(coldest_surface_c >= kMagnusLowC && warmest_surface_c <= kMagnusHighC))
    return problem(AirInput::surface_temperature,
                   "(" + num(coldest_surface_c) + " to " + num(warmest_surface_c) +
                       " C at the surface) is outside [-40, 50] C, the range of the Magnus "
                       "saturation vapour pressure (Alduchov & Eskridge 1996)");
  const double length = body.length_m;
  const std::string size = std::string(body_text(body.kind)) + num(length) + " m";
  // Natural convection: the largest Rayleigh number the run can see.
  for (double ts : {coldest_surface_c, warmest_surface_c}) {
    const AirProperties film = air_properties(0.5 * (ts + air.temperature_c));
    const double ra = rayleigh(film, air.temperature_c - ts, length);
    const double max_ra = body.kind == AirBody::sphere ? kSphereNaturalMaxRa : kChurchillChuMaxRa;
    if (ra > max_ra)
      return problem(AirInput::temperature,
                     "(" + num(air.temperature_c) + " C) against a surface at " + num(ts) +
                         " C gives Ra = " + num(ra) + " on " + size + ", above " + num(max_ra) +
                         ", the top of " +
                         (body.kind == AirBody::sphere ? "Churchill's (1983) sphere correlation"
                                                       : "Churchill & Chu's (1975) correlation"));
  }
  if (air.speed_m_s == 0) return std::nullopt;
  if (body.kind == AirBody::sphere) {
    const AirProperties free = air_properties(air.temperature_c);
    const double re = air.speed_m_s * length / free.kinematic_viscosity_m2_s;
    if (!(re >= kWhitakerMinRe && re <= kWhitakerMaxRe))
      return problem(AirInput::speed, "(" + num(air.speed_m_s) + " m/s) gives Re_D = " + num(re) +
                                          " on " + size +
                                          ", outside [3.5, 7.6e4], the range of Whitaker's (1972) "
                                          "sphere correlation (0 = still air)");
    const double ratio_warm = free.viscosity_pa_s / viscosity(warmest_surface_c);
    const double ratio_cold = free.viscosity_pa_s / viscosity(coldest_surface_c);
    if (!(ratio_warm >= kWhitakerMinViscosityRatio && ratio_cold <= kWhitakerMaxViscosityRatio))
      return problem(AirInput::temperature,
                     "(" + num(air.temperature_c) + " C) with a surface at " +
                         num(coldest_surface_c) + " to " + num(warmest_surface_c) +
                         " C gives mu/mu_s = " + num(ratio_warm) + " to " + num(ratio_cold) +
                         ", outside [1, 3.2], the range of Whitaker's (1972) sphere correlation "
                         "(in a stream the air must not be colder than the surface; use "
                         "speed_m_s = 0 or kind = \"convective\")");
    return std::nullopt;
  }
  const AirProperties film = air_properties(0.5 * (air.temperature_c + coldest_surface_c));
  const double re = air.speed_m_s * length / film.kinematic_viscosity_m2_s;
  if (body.kind == AirBody::horizontal_cylinder) {
    if (re * film.prandtl < kChurchillBernsteinMinRePr)
      return problem(AirInput::speed,
                     "(" + num(air.speed_m_s) + " m/s) gives Re_D Pr = " + num(re * film.prandtl) +
                         " on " + size +
                         ", below 0.2, the bottom of Churchill & Bernstein's (1977) cylinder "
                         "correlation (0 = still air)");
    return std::nullopt;
  }
  if (!(re < kPlateMaxRe && re * film.prandtl >= kPlateMinRePr))
    return problem(AirInput::speed,
                   "(" + num(air.speed_m_s) + " m/s) gives Re_L = " + num(re) + " on " + size +
                       ", outside Re_L Pr >= 100 and Re_L < 5e5, the laminar range of Churchill "
                       "& Ozoe's (1973) flat-plate correlation (0 = still air)");
  return std::nullopt;
}

}  // namespace thaw::sim
