#include "sim/scenario/geometry.h"

namespace thaw::sim {

const char* to_string(Geometry g) {
  switch (g) {
    case Geometry::planar:
      return "planar";
    case Geometry::cylinder:
      return "cylinder";
    case Geometry::sphere:
      return "sphere";
  }
  return "?";
}

bool parse_geometry(const std::string& text, Geometry& out) {
  for (Geometry g : {Geometry::planar, Geometry::cylinder, Geometry::sphere}) {
    if (text == to_string(g)) {
      out = g;
      return true;
    }
  }
  return false;
}

}  // namespace thaw::sim
