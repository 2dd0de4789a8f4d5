#pragma once
// The plain description of one simulation (parsed from a scenario TOML file, or built in code by
// tests and the pipeline): geometry, initial state, boundary conditions, materials and the
// accuracy knobs. Knows nothing of TOML or of how the solver works.
#include <optional>
#include <string>
#include <vector>

#include "sim/scenario/geometry.h"
#include "sim/scenario/interface_record.h"
#include "sim/shape/shape.h"

namespace thaw::sim {

/// Thermal properties of ice and water (SI). Defaults come from data/materials/ice_water.toml.
struct Materials {
  double ice_conductivity_w_mk = 2.22;        ///< k_ice [W/(m K)]
  double ice_density_kg_m3 = 917.0;           ///< rho_ice [kg/m^3]
  double ice_specific_heat_j_kgk = 2050.0;    ///< c_ice [J/(kg K)]
  double water_conductivity_w_mk = 0.56;      ///< k_water [W/(m K)]
  double water_density_kg_m3 = 1000.0;        ///< rho_water [kg/m^3]
  double water_specific_heat_j_kgk = 4186.0;  ///< c_water [J/(kg K)]
  double latent_heat_j_kg = 333400.0;         ///< L [J/kg]
  double melting_point_c = 0.0;               ///< T_m [C]
  /// Buoyancy of the water when it flows ([simulation] flow): water's density curve with its
  /// maximum at 4.03 C, or a linear Boussinesq fluid rho = rho_water (1 - beta (T - T_m)).
  enum class DensityModel { water, linear };
  DensityModel water_density_model = DensityModel::water;
  double water_expansion_per_k = 0;  ///< linear: beta [1/K]
  double water_viscosity_pa_s = 0;   ///< > 0: constant viscosity [Pa s]; 0: water's table

  /// Volumetric heat capacities [J/(m^3 K)] and latent heat per unit volume of ice [J/m^3].
  double ice_heat_capacity() const { return ice_density_kg_m3 * ice_specific_heat_j_kgk; }
  double water_heat_capacity() const { return water_density_kg_m3 * water_specific_heat_j_kgk; }
  double latent_heat_per_volume() const { return ice_density_kg_m3 * latent_heat_j_kg; }
};

enum class InnerBoundary { symmetry, temperature };
enum class OuterBoundary { temperature, convective, flux, insulated, air };

const char* to_string(InnerBoundary kind);
const char* to_string(OuterBoundary kind);

/// The keys of one [outer_boundary] table: the whole body's (Scenario's outer_* fields) or one
/// face's ([outer_boundary.faces.NAME], grid runs). Fields as Scenario's below.
struct OuterBoundarySpec {
  OuterBoundary kind = OuterBoundary::convective;
  double temperature_c = 20.0;
  double heat_transfer_coefficient_w_m2k = 10.0;
  double flux_w_m2 = 0.0;
  double relative_humidity = 0.5;
  double air_speed_m_s = 0.0;
  std::optional<double> surroundings_temperature_c;
  double emissivity = 0.97;
};

/// A face of the body (sim/grid/body_faces.h) with its own [outer_boundary.faces.NAME] table.
struct FaceBoundary {
  std::string face;
  OuterBoundarySpec spec;
};

/// Which solver runs: the 1D radial one (none: `geometry` and [shell] apply) or the grid
/// enthalpy solver on [shape] (geometry = "axisymmetric" | "3d").
enum class GridGeometry { none, axisymmetric, cartesian3d };

/// "" | "axisymmetric" | "3d" (the scenario file's spelling).
const char* to_string(GridGeometry grid);

struct Scenario {
  // [simulation]
  Geometry geometry = Geometry::sphere;  ///< 1D geometry (ignored when grid != none)
  GridGeometry grid = GridGeometry::none;
  double duration_s = 3600.0;       ///< end time [s]
  double output_interval_s = 60.0;  ///< rows of interfaces.csv at t = k * interval [s]
  int cells_per_phase = 48;         ///< finite volumes in each phase (water, ice)
  /// Time-step error tolerance: the estimated local error of one step in the front positions
  /// (relative to outer_radius_m) and temperatures (relative to the largest temperature
  /// difference in the scenario).
  double time_tolerance = 1e-6;
  /// Grid runs: cell edge [m]; 0 picks default_cell_size_m() (sim/grid/grid_rules.h).
  double cell_size_m = 0;
  /// Grid runs: largest time step [s] (steps adapt below it to the temperature and melt change).
  double max_step_s = 10.0;
  /// Grid runs: natural convection in the water (sim/grid/grid_flow.h), or conduction only.
  bool natural_convection = false;

  // [shape] (grid runs only)
  Shape shape;

  // [shell]
  double inner_radius_m = 0.02;  ///< water|ice front at t = 0 [m]; may be 0
  double outer_radius_m = 0.03;  ///< ice surface at t = 0 [m]; may equal inner_radius_m
  double length_m = 0.06;        ///< cylinder: length of the capsule's tube [m] (mesher only)
  double lateral_size_m = 0.1;   ///< planar: lateral size of the slab [m] (mesher only)

  // [water], [ice]
  double water_initial_temperature_c = 10.0;
  double ice_initial_temperature_c = -5.0;

  // [inner_boundary] (planar only may be "temperature")
  InnerBoundary inner_kind = InnerBoundary::symmetry;
  double inner_temperature_c = 0.0;  ///< held wall temperature (kind = temperature) [C]

  // [outer_boundary]
  OuterBoundary outer_kind = OuterBoundary::convective;
  double outer_temperature_c = 20.0;  ///< held surface temperature or air temperature [C]
  double heat_transfer_coefficient_w_m2k = 10.0;  ///< h [W/(m^2 K)] (convective)
  double flux_w_m2 = 0.0;                         ///< heat flux into the ice [W/m^2] (flux)
  // kind = air (sim/boundary/air_model.h): outer_temperature_c is the air's temperature.
  double relative_humidity = 0.5;  ///< of the air, 0..1
  double air_speed_m_s = 0.0;      ///< free-stream speed [m/s]; 0 = still air
  /// Temperature of the walls the surface radiates to [C]; unset: the air's.
  std::optional<double> surroundings_temperature_c;
  double emissivity = 0.97;  ///< of the ice surface, (0, 1]
  /// Grid runs: faces of the body with a condition of their own (a face not named takes the
  /// keys above), in the file's order.
  std::vector<FaceBoundary> outer_faces;

  Materials materials;

  /// Where the scenario came from, for messages (the file name, or what built it in code).
  std::string source_name = "scenario";
};

/// The body's [outer_boundary] keys of `s` (not its faces').
inline OuterBoundarySpec outer_boundary_spec(const Scenario& s) {
  return {
      s.outer_kind,        s.outer_temperature_c, s.heat_transfer_coefficient_w_m2k, s.flux_w_m2,
      s.relative_humidity, s.air_speed_m_s,       s.surroundings_temperature_c,      s.emissivity};
}

/// `s` with `spec` as its [outer_boundary] keys and no faces: a face's condition seen by the
/// rules and the air model, which read those keys.
inline Scenario with_outer_boundary(Scenario s, const OuterBoundarySpec& spec) {
  s.outer_kind = spec.kind;
  s.outer_temperature_c = spec.temperature_c;
  s.heat_transfer_coefficient_w_m2k = spec.heat_transfer_coefficient_w_m2k;
  s.flux_w_m2 = spec.flux_w_m2;
  s.relative_humidity = spec.relative_humidity;
  s.air_speed_m_s = spec.air_speed_m_s;
  s.surroundings_temperature_c = spec.surroundings_temperature_c;
  s.emissivity = spec.emissivity;
  s.outer_faces.clear();
  return s;
}

}  // namespace thaw::sim
