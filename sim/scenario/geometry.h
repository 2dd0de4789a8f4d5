#pragma once
// The shell's 1D geometry (planar slab, cylinder, sphere): a scenario value shared by the solver,
// its output files and the mesher. Knows nothing of files.
#include <string>

namespace thaw::sim {

enum class Geometry { planar, cylinder, sphere };

/// "planar" | "cylinder" | "sphere".
const char* to_string(Geometry geometry);
/// Inverse of to_string; returns false for anything else.
bool parse_geometry(const std::string& text, Geometry& out);

}  // namespace thaw::sim
