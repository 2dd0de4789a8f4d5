#include "sim/grid/grid_field.h"

#include <algorithm>
#include <cmath>

#include "base/number_text.h"

namespace thaw::sim {

std::size_t GridField::cell_count() const {
  return static_cast<std::size_t>(cells[0]) * static_cast<std::size_t>(cells[1]) *
         static_cast<std::size_t>(cells[2]);
}

std::optional<GridFieldProblem> find_header_problem(const GridField& f) {
  auto num = [](double v) { return shortest_text(v); };
  for (int c : f.cells)
    if (c <= 0)
      return GridFieldProblem{"cells", "cell count " + std::to_string(c) + " is not positive"};
  if (f.geometry == GridField::Geometry::axisymmetric && f.cells[2] != 1)
    return GridFieldProblem{
        "cells", "an axisymmetric field must have cells[2] = 1, got " + std::to_string(f.cells[2])};
  if (!std::isfinite(f.time_s) || f.time_s < 0)
    return GridFieldProblem{"time_s", "time " + num(f.time_s) + " s is negative or not finite"};
  if (!(f.spacing_m >= kMinFieldSpacingM && f.spacing_m <= kMaxFieldSpacingM))
    return GridFieldProblem{"spacing_m", "cell spacing " + num(f.spacing_m) + " m is outside [" +
                                             num(kMinFieldSpacingM) + ", " +
                                             num(kMaxFieldSpacingM) + "] m"};
  if (f.geometry == GridField::Geometry::axisymmetric && (f.origin_m[0] != 0 || f.origin_m[2] != 0))
    return GridFieldProblem{"origin_m",
                            "an axisymmetric field starts on the axis (x = z = 0), got x = " +
                                num(f.origin_m[0]) + ", z = " + num(f.origin_m[2])};
  for (int a = 0; a < 3; ++a) {
    // Both corners of the grid (an axisymmetric grid reaches nr cells to either side of the axis).
    const double lo = f.origin_m[a];
    const double hi = lo + f.cells[a] * f.spacing_m;
    const double reach = f.geometry == GridField::Geometry::axisymmetric && a != 1
                             ? f.cells[0] * f.spacing_m
                             : std::max(std::abs(lo), std::abs(hi));
    if (!std::isfinite(lo) || !(reach <= kMaxFieldCoordinateM))
      return GridFieldProblem{
          "origin_m", "the grid reaches " + num(std::isfinite(lo) ? reach : lo) +
                          " m from the origin along axis " + "xyz"[a] + " (origin " + num(lo) +
                          " m, " + std::to_string(f.cells[a]) + " cells of " + num(f.spacing_m) +
                          " m); at most " + num(kMaxFieldCoordinateM) + " m"};
  }
  return std::nullopt;
}

const char* to_string(GridField::Geometry geometry) {
  return geometry == GridField::Geometry::axisymmetric ? "axisymmetric" : "cartesian3d";
}

}  // namespace thaw::sim
