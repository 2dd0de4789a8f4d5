#pragma once
// A scenario's [outer_boundary] kind = "air" as the air model's inputs: the air itself and the
// body the 1D geometries present to it. The one place that maps scenario fields onto
// sim/boundary/air_model.h (the rules, the 1D solver and the grid solver all read it).
#include <optional>

#include "sim/boundary/air_model.h"
#include "sim/scenario/scenario.h"

namespace thaw::sim {

/// The air of a scenario (its outer_boundary keys; surroundings default to the air's temperature).
Air scenario_air(const Scenario& scenario);

/// The body a 1D geometry presents to the air when its ice surface is at radius b [m]:
/// sphere of D = 2b; cylinder: horizontal (the capsule lies along z), D = 2b; planar: a
/// vertical face of height shell.lateral_size_m.
AirBodySize radial_air_body(const Scenario& scenario, double outer_radius_m);

/// The body a scenario presents to the air at t = 0: the 1D geometries' radial_air_body at the
/// outer radius; grid runs a sphere of the outer shape's volume (box: edges unrounded), as the
/// grid solver uses; nullopt for an OBJ outer shape (its volume is known only once meshed).
std::optional<AirBodySize> scenario_air_body(const Scenario& scenario);

/// The dotted scenario key of an air-model input ("outer_boundary.speed_m_s").
const char* air_input_key(AirInput input);

}  // namespace thaw::sim
