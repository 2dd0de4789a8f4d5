#pragma once
// One output time of a 1D run's fronts and volumes: what the solver produces and
// sim/format/interface_history.h writes as a row of interfaces.csv. Knows nothing of files.

namespace thaw::sim {

/// One row of interfaces.csv. Planar geometry: positions [m] measured from the inner end and
/// volumes per unit area [m^3/m^2]; cylinder: volumes per unit length [m^3/m].
struct InterfaceRecord {
  long step = 0;                    ///< output index, 0-based, consecutive
  double time_s = 0;                ///< simulated time [s]
  double inner_radius_m = 0;        ///< water|ice front s(t) [m]; 0 when no liquid is left
  double outer_radius_m = 0;        ///< ice|air surface b(t) [m]; == inner when no ice is left
  double liquid_volume_m3 = 0;      ///< volume of the liquid core
  double ice_volume_m3 = 0;         ///< volume of the ice shell
  double energy_balance_error = 0;  ///< |dH - heat in| / reference energy, relative
};

}  // namespace thaw::sim
