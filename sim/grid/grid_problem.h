#pragma once
// The discrete input of the grid enthalpy solver: a uniform grid of cubic cells (axisymmetric
// (r, y) rings or 3D Cartesian boxes), each holding a fraction of material (ice and/or water;
// the rest is air) with its enthalpy, plus the boundary conditions. Built from a scenario's
// [shape] (sim/grid/grid_builder.h) or directly by tests. Knows nothing of TOML or files.
#include <array>
#include <cstdint>
#include <vector>

#include "sim/boundary/air_model.h"
#include "sim/flow/fluid_model.h"
#include "sim/grid/grid_field.h"
#include "sim/scenario/scenario.h"
#include "sim/shape/shape.h"

namespace thaw::sim {

/// The condition at the material | air surface (as an [outer_boundary] table).
struct SurfaceCondition {
  OuterBoundary kind = OuterBoundary::convective;
  double temperature_c = 20;                    ///< held surface or air temperature [C]
  double heat_transfer_coefficient_w_m2k = 10;  ///< convective h [W/(m^2 K)]
  double flux_w_m2 = 0;                         ///< flux kind: heat into the body [W/m^2]
  Air air;                                      ///< air kind: the room
};

/// A wall of the grid's box: insulated (also the axis r = 0) or held at a temperature. Walls
/// touching material only occur in validation problems: scenario grids are padded with air.
struct GridWall {
  bool held = false;         ///< false: zero flux
  double temperature_c = 0;  ///< held wall temperature [C]
};

struct GridProblem {
  GridField::Geometry geometry = GridField::Geometry::cartesian3d;
  std::array<int, 3> cells{0, 0, 0};        ///< as GridField::cells
  std::array<double, 3> origin_m{0, 0, 0};  ///< as GridField::origin_m
  double spacing_m = 0;                     ///< cell edge [m]
  /// Per cell (GridField index order): volume fraction of material (ice + water) [0, 1] and
  /// its enthalpy per unit volume of material relative to ice at T_m [J/m^3]: ice below 0,
  /// melting between 0 and rho_ice L, water above.
  std::vector<double> material_fraction, enthalpy_j_m3;
  Materials materials;
  /// Condition at the material | air surface (as [outer_boundary]).
  OuterBoundary surface_kind = OuterBoundary::convective;
  double surface_temperature_c = 20;            ///< held surface or air temperature [C]
  double heat_transfer_coefficient_w_m2k = 10;  ///< convective h [W/(m^2 K)]
  double flux_w_m2 = 0;                         ///< flux kind: heat into the body [W/m^2]
  /// air kind: the room, and the diameter of the sphere of the body's volume (ice and enclosed
  /// water) at t = 0 [m]; the solver follows the volume as it melts.
  Air air;
  double air_diameter_m = 0;
  /// The body's faces (sim/grid/body_faces.h: those of a box, a cylinder, or one surface), whose
  /// heat the solver books apart, and per cell the face of its centre, for cells without a
  /// surface normal (empty: face 0).
  ShapeKind face_shape = ShapeKind::sphere;
  std::vector<std::uint8_t> face_of_cell;
  /// Per face of face_shape, its own surface condition ([outer_boundary.faces.NAME]; a face not
  /// named has the one above); empty: every face has the one above. A surface cell takes the
  /// faces' conditions in the proportions of body_face_weights (by its surface's normal).
  std::vector<SurfaceCondition> face_conditions;
  /// Grid walls, order x-, x+, y-, y+, z-, z+ (axisymmetric: x- is the axis, z unused).
  std::array<GridWall, 6> walls{};
  /// Melt drains away where it touches air that is connected to the grid's border.
  bool drain = true;
  /// Natural convection in the water (sim/grid/grid_flow.h); false: conduction only.
  bool flow = false;
  /// The water's buoyancy and viscosity when flow is on.
  flow::FluidModel fluid;
  /// Time stepping: > 0 constant steps (validation), else adaptive up to max_step_s.
  double fixed_step_s = 0;
  double max_step_s = 10;
  /// The run's end [s], the runaway guard's horizon (0: the target of each advance_to).
  double end_time_s = 0;
  /// Adaptive step targets: largest temperature change [K] and liquid-fraction change per step.
  double step_temperature_change_k = 1.0;
  double step_melt_fraction = 0.25;
};

/// Enthalpy per unit volume [J/m^3] of material at temperature t_c [C]: ice (below T_m),
/// water (above), ice at T_m for exactly T_m.
double enthalpy_of_temperature(const Materials& m, double t_c, bool liquid);

}  // namespace thaw::sim
