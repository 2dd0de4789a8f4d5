#pragma once
// The rules of a grid run's [shape] and resolution, in one place for the parser, the builder
// and validate_scenario: sizes, kinds allowed per geometry, the cavity strictly inside the outer
// body, the default cell size and the thinnest wall it must resolve. Knows nothing of TOML.
#include <optional>
#include <string>

#include "sim/flow/fluid_model.h"
#include "sim/scenario/scenario.h"
#include "sim/shape/signed_distance.h"

namespace thaw::sim {

/// A wall must be at least this many cells thick.
constexpr double kMinWallCells = 3.0;
/// Default resolution: cells across the outer body's largest extent (and at least
/// kDefaultWallCells across the thinnest wall).
constexpr double kDefaultCellsAcross3d = 48.0;
constexpr double kDefaultCellsAcrossAxisymmetric = 120.0;
constexpr double kDefaultWallCells = 5.0;
/// Largest grid accepted [cells].
constexpr double kMaxGridCells = 8.0e6;

/// The widest temperature difference the scenario rules admit [K]: air from absolute zero to
/// 1000 C (sim/scenario/scenario_rules.cpp).
constexpr double kWidestTemperatureSpanK = 1273.15;
/// The grid solver's adaptive control aims at this temperature change per step by default
/// (GridProblem::step_temperature_change_k) [K].
constexpr double kStepTemperatureChangeK = 1.0;

/// Smallest accepted simulation.max_step_s for cells of edge cell_m [s]: the time heat takes to
/// diffuse across one cell, tau = dx^2 / alpha (alpha the larger of ice's and water's
/// diffusivity), times kStepTemperatureChangeK / kWidestTemperatureSpanK. A cell's temperature
/// changes at most about dT / tau per unit time with dT the difference across it, so even the
/// widest admitted difference changes it by no more than the adaptive control's target per step
/// within this time: a cap below it never makes a step more accurate, it only multiplies the
/// steps (a cap of 1e-9 s asks for 3.6e12 steps per hour and ran for ever).
double smallest_max_step_s(const Materials& materials, double cell_m);

/// The water's buoyancy and viscosity of a scenario's materials ([materials] water_density_model,
/// water_expansion_per_k, water_viscosity_pa_s): the flow solver's fluid.
flow::FluidModel fluid_model_of(const Materials& materials);

/// Cells that must span the water's thermal boundary layer when it flows.
constexpr double kMinBoundaryLayerCells = 2.0;

/// The scale of the water's flow at the start of a run with natural convection: L the water's
/// largest extent (the cavity's, or the body's when it is all water) [m], Ra = g (rho_max -
/// rho_min) / rho_0 L^3 / (nu alpha) over the water's temperatures [t_lo, t_hi] (from the
/// melting point to the initial water's, or over the held faces'; the 4 C maximum included; nu
/// at their mean, alpha =
/// k_w / (rho c)_w), and the thermal boundary layer along its walls, delta = L Ra^(-1/4) [m]
/// (laminar natural convection along a wall: the scale analysis of Bejan, Convection Heat
/// Transfer, 4th ed. 2013, sec. 4.2, delta_T ~ H Ra_H^(-1/4) for Pr >= 1).
struct FlowScale {
  double length_m = 0, rayleigh = 0, boundary_layer_m = 0;
};
FlowScale water_flow_scale(const Scenario& s, double extent_m, double t_lo, double t_hi);
/// water_flow_scale of a cavity of largest extent `cavity_extent_m` whose water spans
/// [T_m, T_water].
FlowScale cavity_flow_scale(const Scenario& s, double cavity_extent_m);

struct GridRuleProblem {
  std::string key;  ///< dotted key, e.g. "shape.cavity"
  std::string message;
};

/// The signed distance of a shape (loads OBJ files; throws thaw::UserError("", key, problem)).
SignedDistance make_signed_distance(const ShapeSpec& spec, const std::string& key);

/// Thinnest ice between the cavity and the outer surface [m] (negative: the cavity pokes out),
/// or the outer body's smallest half-extent when there is no cavity.
double thinnest_wall_m(const SignedDistance& outer, const SignedDistance* cavity);

/// cell_size_m if set, else min(largest extent / cells across, thinnest wall / kDefaultWallCells).
double effective_cell_size_m(const Scenario& s);

/// First violated rule of a grid scenario (std::nullopt if none; nothing checked for 1D).
std::optional<GridRuleProblem> find_grid_problem(const Scenario& s);

}  // namespace thaw::sim
