#pragma once
// The [shape] description of a body for the axisymmetric and 3D solvers: an outer solid and an
// optional cavity, each a box (optionally with rounded edges), a sphere, a vertical cylinder or
// a closed OBJ mesh. Plain data, parsed from TOML by sim/scenario, turned into signed distances
// by sim/shape/signed_distance.h. Knows nothing of grids or TOML.
#include <array>
#include <optional>
#include <string>

namespace thaw::sim {

enum class ShapeKind { box, sphere, cylinder, obj };

/// "box" | "sphere" | "cylinder" | "obj".
const char* to_string(ShapeKind kind);

struct ShapeSpec {
  ShapeKind kind = ShapeKind::box;
  std::array<double, 3> center_m{0, 0, 0};  ///< centre (y is vertical) [m]
  std::array<double, 3> size_m{0, 0, 0};    ///< box: full edge lengths [m]
  double edge_radius_m = 0;                 ///< box: rounding of edges and corners [m]
  double radius_m = 0;                      ///< sphere, cylinder [m]
  double height_m = 0;                      ///< cylinder: length along the vertical y axis [m]
  std::string file;                         ///< obj: path (resolved against the scenario's folder)
  double scale = 1;                         ///< obj: vertex coordinates are multiplied by this
  std::array<double, 3> translate_m{0, 0, 0};  ///< obj: then moved by this [m]
};

struct Shape {
  ShapeSpec outer;
  std::optional<ShapeSpec> cavity;  ///< none: solid ice
  /// [shape] fill = "water": the outer body is all water at t = 0 (no ice, no cavity); ice forms
  /// where it freezes. The water stays where it is (it does not drain): its faces hold it.
  bool fill_water = false;
};

}  // namespace thaw::sim
