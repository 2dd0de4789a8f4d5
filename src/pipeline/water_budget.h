#pragma once
// Where the shell's water is at each film frame: in the ice, in the liquid core, or in the
// puddle on the floor. Mass conservation applied to the solver's outputs (interfaces.csv radii),
// so that no water vanishes from the film. Knows nothing of meshes or rendering.
//
// The solver (docs/simulate.md) neglects the density change at the water|ice front: both phases
// keep their volume, so melting 1 m^3 of ice adds 1 m^3 to the core although it is only
// rho_ice / rho_water = 0.917 m^3 of water. Its ice volumes are taken as real ice (rho_ice), and
// the rest follows from mass conservation:
//   drained melt   the ice ablated at the outer surface, V(b0) - V(b): the sum of ice and core
//                  volume changes only there, since the front converts volume one to one;
//                  mass rho_ice (V(b0) - V(b)), drained to the puddle at once
//   core water     rho_water V(s0) + rho_ice (V(s) - V(s0)): the ice melted (or frozen) at the
//                  front moves rho_ice per unit of solver volume. Its real volume m / rho_water is
//                  up to 8.3 % of the melted ice less than the drawn cavity V(s) (a vapour void)
//   spilled water  once the ice is gone (break-through), the core water joins the puddle
//   puddle         drained melt + spilled water, volume = mass / rho_water
// so that rho_ice V_ice + m_core + m_puddle = rho_ice V_ice(0) + rho_water V_liquid(0) at every
// frame. V(r) is the volume inside the drawn surface at distance r from the shell's core
// (docs/mesh.md: sphere, capsule, rounded slab), so the budget is of the object in the film,
// whose volumes are 3-D even where interfaces.csv gives them per m (cylinder) or per m^2 (planar).
#include <vector>

#include "sim/format/interface_history.h"

namespace thaw::pipeline {

/// Volume enclosed by the drawn surface at distance `r_m` from the core [m^3]: sphere
/// 4/3 pi r^3; capsule pi r^2 L + 4/3 pi r^3; rounded slab 2 S^2 r + 2 pi S r^2 + 4/3 pi r^3.
double shell_surface_volume_m3(const sim::ShellGeometry& geometry, double r_m);

struct WaterBudget {
  double ice_mass_kg = 0;           ///< rho_ice (V(b) - V(s))
  double core_water_mass_kg = 0;    ///< water still held by the ice (0 once spilled)
  double drained_melt_mass_kg = 0;  ///< rho_ice (V(b0) - V(b)), on the floor
  double spilled_mass_kg = 0;       ///< the core's water, once the ice is gone
  double puddle_volume_m3 = 0;      ///< (drained + spilled) / rho_water
  double total_mass_kg() const {
    return ice_mass_kg + core_water_mass_kg + drained_melt_mass_kg + spilled_mass_kg;
  }
};

/// One budget per row of `rows` (the first row is the initial state). Water spills at the first
/// row without ice after a row with ice (break-through) and stays spilled; a drop that starts
/// without ice (water_drop_freezing) holds its water until it has frozen a shell.
std::vector<WaterBudget> water_budget(const std::vector<sim::InterfaceRecord>& rows,
                                      const sim::ShellGeometry& geometry, double ice_density_kg_m3,
                                      double water_density_kg_m3);

}  // namespace thaw::pipeline
