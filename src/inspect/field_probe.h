#pragma once
// The temperature of a grid run's material (sim/format/grid_field_file.h) at any point of the
// meshes' frame, for the surface temperature point data of the hand-off .vtp files. Trilinear over
// the eight nearest cell centres, each weighted by its material (ice + water) fraction: a surface
// vertex lies between material cells and the air padding around the body, and the air's held
// temperature is not the surface's. Knows nothing of VTK or meshes.
#include <array>

#include "sim/format/grid_field_file.h"

namespace thaw::inspect {

/// Temperature [C] of the material of `field` at `point_m` (the field's coordinates; an
/// axisymmetric field is revolved about the y axis, r = hypot(x, z)). Outside the cell centres'
/// box the nearest centres' values are held (constant extrapolation; on the axis this is the
/// field's symmetry). Where none of the eight cells holds material (a vertex that smoothing moved
/// off a thin remnant), the temperature of the nearest material cell within two cells; where
/// there is none either, the plain trilinear value.
double material_temperature_c(const sim::GridField& field, const std::array<double, 3>& point_m);

}  // namespace thaw::inspect
