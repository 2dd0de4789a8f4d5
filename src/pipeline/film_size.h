#pragma once
// What size of piece `thaw run` films, checked when the scenario is parsed (issue 27): the keys
// are in metres, and a radius typed in centimetres (outer_radius_m = 3, a ball 6 m across) used
// to simulate, then mesh for ever or fail at the mesh stage with a hint for an option thaw run
// does not have. Two rules: the piece is at most kMaxFilmExtentM across (a hand-sized to
// sculpture-sized object, as the camera, floor and puddle are made for), and its largest surface
// needs at most kMaxTrianglesPerSurface triangles with the scenario's [mesh] options. The lower
// end (a 1 um shell) is the solver's rule (sim/scenario/scenario_rules.cpp: 0.1 mm). Knows the
// scenario and the mesher's estimate only.
#include "src/pipeline/run_scenario.h"

namespace thaw {
class TomlTable;
}

namespace thaw::pipeline {

/// The largest piece thaw run films, across [m]: 2 m (a 1 m ball; the shipped scenarios are
/// 2-10 cm).
inline constexpr double kMaxFilmExtentM = 2.0;

/// Throws thaw::UserError(file, line and key, problem) naming the size key in metres, or the
/// [mesh] key that asks for too many triangles.
void check_film_size(const TomlTable& root, const RunScenario& scenario);

}  // namespace thaw::pipeline
