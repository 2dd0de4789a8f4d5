#pragma once
// The liquid's buoyancy and viscosity as functions of temperature, for the Boussinesq flow
// solver: water's density curve with its maximum near 4 C, or a linear Boussinesq fluid (the
// classic benchmarks at any Prandtl number); water's viscosity from a cited table, or a constant.
// Knows nothing of grids or files.

namespace thaw::sim::flow {

/// Density of liquid water [kg/m^3] at temperature_c (0-20 C and somewhat beyond):
/// rho = 999.972 (1 - 9.2793e-6 |T - 4.0293|^1.894816), the Gebhart & Mollendorf (1977) form
/// used by Michalek & Kowalewski (2003, TASK Quarterly 7(3):389). rho(0) = 999.842,
/// rho(4.0293) = 999.972 (the maximum), rho(10) = 999.698, rho(20) = 998.204.
double water_density_kg_m3(double temperature_c);
/// Largest density of liquid water [kg/m^3] (at 4.0293 C).
inline constexpr double kWaterDensityMaxKgM3 = 999.972;
inline constexpr double kWaterDensityMaxTemperatureC = 4.0293;

/// Dynamic viscosity of liquid water at 0.1 MPa [Pa s], linear between the table's points
/// (0, 5, ..., 40 C; CRC Handbook of Chemistry and Physics, 97th ed., "Viscosity of Liquids",
/// after IAPWS 2008: 1.793, 1.519, 1.307, 1.138, 1.002, 0.890, 0.797, 0.719, 0.653 mPa s),
/// held at the end values outside [0, 40] C (supercooled water is not modelled).
double water_viscosity_pa_s(double temperature_c);

struct FluidModel {
  enum class Density { water, linear };
  Density density = Density::water;
  /// reference density rho_0 [kg/m^3]: the density of the Boussinesq momentum equation
  double reference_density_kg_m3 = kWaterDensityMaxKgM3;
  /// linear: rho = rho_0 (1 - beta (T - T_0)); beta [1/K] and T_0 [C]
  double expansion_per_k = 0;
  double reference_temperature_c = 0;
  /// > 0: a constant dynamic viscosity [Pa s]; 0: water's table above
  double viscosity_pa_s = 0;
  /// gravitational acceleration [m/s^2], acting along -y
  double gravity_m_s2 = 9.81;

  /// Boussinesq buoyancy along +y [m/s^2]: -g (rho(T) - rho_ref) / rho_0, rho_ref being
  /// rho(T_0) (linear) or water's largest density (a constant shift only moves the pressure).
  double buoyancy_m_s2(double temperature_c) const;
  /// nu(T) = mu(T) / rho_0 [m^2/s].
  double kinematic_viscosity_m2_s(double temperature_c) const;
};

}  // namespace thaw::sim::flow
