#pragma once
// The enthalpy-temperature relation of the grid solver's material (ice and water), per unit
// volume of material: H < 0 ice below T_m, 0 <= H <= L_v melting at T_m (liquid fraction
// H / L_v), H > L_v water above T_m; T(H) is piecewise linear with kinks at 0 and L_v (Voller
// & Prakash 1987). Throughout sim/grid, H is this enthalpy per unit volume of material
// [J/m^3] and nothing else (a film's heat transfer coefficient is `film`, the cell edge `dx`,
// the step `dt`). Knows nothing of grids or files.
#include <algorithm>

#include "sim/scenario/scenario.h"

namespace thaw::sim {

struct PhaseRelation {
  explicit PhaseRelation(const Materials& mat)
      : latent(mat.latent_heat_per_volume()),
        tm(mat.melting_point_c),
        ci(mat.ice_heat_capacity()),
        cw(mat.water_heat_capacity()),
        ki(mat.ice_conductivity_w_mk),
        kw(mat.water_conductivity_w_mk) {}

  double latent = 0;      ///< L_v: latent heat per unit volume [J/m^3]
  double tm = 0;          ///< melting point [C]
  double ci = 0, cw = 0;  ///< volumetric heat capacities of ice and water [J/(m^3 K)]
  double ki = 0, kw = 0;  ///< conductivities of ice and water [W/(m K)]

  /// T(H) [C].
  double temperature(double H) const {
    if (H < 0) return tm + H / ci;
    if (H > latent) return tm + (H - latent) / cw;
    return tm;
  }
  /// Liquid fraction of the material, H / L_v clamped to [0, 1].
  double liquid(double H) const { return std::clamp(H / latent, 0.0, 1.0); }
  /// Fraction-weighted conductivity [W/(m K)].
  double conductivity(double H) const {
    const double f = liquid(H);
    return (1 - f) * ki + f * kw;
  }
  /// On the melting plateau (front cell): 0 <= H <= L_v.
  bool melting(double H) const { return H >= 0 && H <= latent; }
};

}  // namespace thaw::sim
