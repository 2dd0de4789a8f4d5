#include "sim/grid/grid_field.h"

namespace thaw::sim {

std::size_t GridField::cell_count() const {
  return static_cast<std::size_t>(cells[0]) * static_cast<std::size_t>(cells[1]) *
         static_cast<std::size_t>(cells[2]);
}

const char* to_string(GridField::Geometry geometry) {
  return geometry == GridField::Geometry::axisymmetric ? "axisymmetric" : "cartesian3d";
}

}  // namespace thaw::sim
