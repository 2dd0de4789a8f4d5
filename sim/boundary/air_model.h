#pragma once
// The heat flux from room air into an ice (or water) surface: natural and forced convection from
// published correlations combined as (Nu_f^3 + Nu_n^3)^(1/3), thermal radiation to the
// surroundings, and condensation or evaporation of water vapour by the Chilton-Colburn analogy.
// Pure functions of SI inputs: knows nothing of scenarios, files or solvers. Every correlation,
// its source and its range of validity: docs/simulate.md, "The air around the ice".
#include <optional>
#include <string>

namespace thaw::sim {

/// The air far from the body and the room around it.
struct Air {
  double temperature_c = 20.0;               ///< T_inf [C]
  double relative_humidity = 0.5;            ///< phi, 0..1 (over liquid water)
  double speed_m_s = 0.0;                    ///< free-stream speed [m/s]; 0 = still air
  double surroundings_temperature_c = 20.0;  ///< T_sur of the walls the surface sees [C]
  double emissivity = 0.97;                  ///< of the surface, (0, 1] (ice: 0.97)
};

/// Which correlations apply. Sphere: Churchill 1983 (natural) + Whitaker 1972 (forced).
/// Horizontal cylinder in cross flow: Churchill & Chu 1975b + Churchill & Bernstein 1977.
/// Vertical surface of height H in flow along it: Churchill & Chu 1975a + Churchill & Ozoe 1973.
enum class AirBody { sphere, horizontal_cylinder, vertical_surface };

const char* to_string(AirBody body);

/// The body the correlations see.
struct AirBodySize {
  AirBody kind = AirBody::sphere;
  /// Sphere and cylinder: the diameter D; vertical surface: its height H [m].
  double length_m = 0;
};

/// Dry air at 1 atm (ideal gas; Sutherland's laws for viscosity and conductivity, White,
/// "Viscous Fluid Flow", 3rd ed. 2006, eqs. 1-36 and 1-41 with Table 1-2 and 1-3) and the
/// diffusivity of water vapour in it (Incropera et al., 7th ed., Table A.8: 0.26e-4 m^2/s at
/// 298 K, scaled as T^(3/2)).
struct AirProperties {
  double density_kg_m3 = 0;
  double specific_heat_j_kgk = 0;
  double conductivity_w_mk = 0;
  double viscosity_pa_s = 0;               ///< dynamic viscosity mu
  double kinematic_viscosity_m2_s = 0;     ///< nu = mu / rho
  double thermal_diffusivity_m2_s = 0;     ///< alpha = k / (rho c_p)
  double prandtl = 0;                      ///< nu / alpha
  double vapour_diffusivity_m2_s = 0;      ///< D_AB of water vapour in air
  double expansion_coefficient_per_k = 0;  ///< beta = 1 / T (ideal gas)
};
AirProperties air_properties(double temperature_c);

/// Saturation vapour pressure over liquid water [Pa]: the Magnus form of Alduchov & Eskridge
/// 1996 (J. Appl. Meteor. 35, 601), e_s = 610.94 exp(17.625 T / (T + 243.04)), T in C, within
/// 0.4 % of the reference from -40 to 50 C.
double saturation_vapour_pressure_pa(double temperature_c);
/// Latent heat of vaporisation of water at T [J/kg]: 2.501e6 - 2370 T (Rogers & Yau, "A Short
/// Course in Cloud Physics", 1989, sec. 2.2; linear fit, 0.1 % from -40 to 40 C).
double vaporisation_heat_j_kg(double temperature_c);

// The correlations (mean Nusselt numbers), each within its own range (see docs/simulate.md).
/// Churchill 1983: sphere, natural convection; Ra_D <= 1e11, Pr >= 0.7.
double nusselt_sphere_natural(double rayleigh, double prandtl);
/// Whitaker 1972: sphere, forced; 3.5 <= Re_D <= 7.6e4, 0.71 <= Pr <= 380, 1 <= mu/mu_s <= 3.2.
double nusselt_sphere_forced(double reynolds, double prandtl, double viscosity_ratio);
/// Churchill & Chu 1975b: horizontal cylinder, natural; Ra_D <= 1e12.
double nusselt_horizontal_cylinder_natural(double rayleigh, double prandtl);
/// Churchill & Bernstein 1977: cylinder in cross flow; Re_D Pr >= 0.2.
double nusselt_cylinder_forced(double reynolds, double prandtl);
/// Churchill & Chu 1975a: vertical plate, natural, whole range; 0.1 <= Ra_H <= 1e12.
double nusselt_vertical_natural(double rayleigh, double prandtl);
/// Churchill & Ozoe 1973: laminar flat plate in parallel flow, mean over length L;
/// Re_L < 5e5 (laminar), Re_L Pr >= 100.
double nusselt_plate_forced(double reynolds, double prandtl);
/// Mixed convection (Churchill 1977, AIChE J. 23, 10): (Nu_f^3 + Nu_n^3)^(1/3).
double nusselt_mixed(double forced, double natural);

/// The flux into the surface and its parts; positive heats the surface [W/m^2].
struct AirFlux {
  double convection_w_m2 = 0;
  double radiation_w_m2 = 0;
  double latent_w_m2 = 0;       ///< condensation (> 0) or evaporation (< 0)
  double mass_flux_kg_m2s = 0;  ///< vapour condensing on the surface (< 0: evaporating)
  double nusselt_natural = 0;
  double nusselt_forced = 0;                   ///< 0 in still air
  double heat_transfer_coefficient_w_m2k = 0;  ///< convective h
  double mass_transfer_coefficient_m_s = 0;    ///< h_m = h / (rho c_p Le^(2/3))
  double total_w_m2() const { return convection_w_m2 + radiation_w_m2 + latent_w_m2; }
};

/// The mean flux over a body of size `body` whose surface is at `surface_temperature_c` (wet:
/// its vapour pressure is saturation over water at that temperature). Natural-convection
/// properties at the film temperature (T_s + T_inf)/2; Whitaker's at T_inf with mu_s at T_s (as
/// he fitted them); the other forced correlations at the film temperature.
AirFlux air_heat_flux(const Air& air, const AirBodySize& body, double surface_temperature_c);

/// The input a broken range concerns (the scenario maps it to its key).
enum class AirInput {
  temperature,
  relative_humidity,
  speed,
  surroundings_temperature,
  emissivity,
  surface_temperature  ///< the run's surface temperatures (initial ice / water, melting point)
};

/// A range broken by an input and the message naming its value, the correlation and the range.
struct AirProblem {
  AirInput input;
  std::string message;
};

/// The first input outside a correlation's range, checked over the surface temperatures the
/// run can see (`coldest_surface_c` .. `warmest_surface_c`) at the body's size now; nullopt when
/// every correlation holds. A body that shrinks
/// below the ranges' lower ends during a run carries the correlations on towards their common
/// limit, conduction (Nu = 2 for a sphere), as documented.
std::optional<AirProblem> find_air_problem(const Air& air, const AirBodySize& body,
                                           double coldest_surface_c, double warmest_surface_c);

}  // namespace thaw::sim
