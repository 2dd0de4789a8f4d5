#include "sim/boundary/scenario_air.h"

#include <cmath>
#include <numbers>

namespace thaw::sim {

Air scenario_air(const Scenario& s) {
  Air air;
  air.temperature_c = s.outer_temperature_c;
  air.relative_humidity = s.relative_humidity;
  air.speed_m_s = s.air_speed_m_s;
  air.surroundings_temperature_c = s.surroundings_temperature_c.value_or(s.outer_temperature_c);
  air.emissivity = s.emissivity;
  return air;
}

AirBodySize radial_air_body(const Scenario& s, double outer_radius_m) {
  switch (s.geometry) {
    case Geometry::sphere:
      return {AirBody::sphere, 2.0 * outer_radius_m};
    case Geometry::cylinder:
      return {AirBody::horizontal_cylinder, 2.0 * outer_radius_m};
    case Geometry::planar:
      return {AirBody::vertical_surface, s.lateral_size_m};
  }
  return {};
}

std::optional<AirBodySize> scenario_air_body(const Scenario& s) {
  if (s.grid == GridGeometry::none) return radial_air_body(s, s.outer_radius_m);
  const ShapeSpec& o = s.shape.outer;
  switch (o.kind) {
    case ShapeKind::sphere:
      return AirBodySize{AirBody::sphere, 2 * o.radius_m};
    case ShapeKind::cylinder:  // pi r^2 h = pi D^3 / 6
      return AirBodySize{AirBody::sphere, std::cbrt(6 * o.radius_m * o.radius_m * o.height_m)};
    case ShapeKind::box:
      return AirBodySize{AirBody::sphere,
                         std::cbrt(6 * o.size_m[0] * o.size_m[1] * o.size_m[2] / std::numbers::pi)};
    case ShapeKind::obj:
      return std::nullopt;
  }
  return std::nullopt;
}

const char* air_input_key(AirInput input) {
  switch (input) {
    case AirInput::temperature:
      return "outer_boundary.temperature_c";
    case AirInput::relative_humidity:
      return "outer_boundary.relative_humidity";
    case AirInput::speed:
      return "outer_boundary.speed_m_s";
    case AirInput::surroundings_temperature:
      return "outer_boundary.surroundings_temperature_c";
    case AirInput::emissivity:
      return "outer_boundary.emissivity";
    case AirInput::surface_temperature:
      return "ice.initial_temperature_c";
  }
  return "outer_boundary.kind";
}

}  // namespace thaw::sim
