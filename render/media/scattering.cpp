#include "render/media/scattering.h"

#include <cmath>
#include <sstream>

namespace thaw::render::media {

namespace {
std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
}  // namespace

double bubble_scattering_per_m(double air_fraction, double radius_m) {
  return 1.5 * air_fraction / radius_m;
}

std::optional<std::string> scattering_problem(double per_m) {
  if (per_m >= 0.0 && per_m <= kMaxScatteringPerM) return std::nullopt;  // false for NaN
  return "must be between 0 and " + num(kMaxScatteringPerM) + " per metre (got " + num(per_m) + ")";
}

std::optional<std::string> asymmetry_problem(double g) {
  if (g > -1.0 && g < 1.0) return std::nullopt;
  return "must be in (-1, 1) (got " + num(g) + ")";
}

std::optional<std::string> air_fraction_problem(double f) {
  if (f >= 0.0 && f < 1.0) return std::nullopt;
  return "must be in [0, 1) (got " + num(f) + ")";
}

std::optional<std::string> bubble_radius_problem(double radius_m) {
  if (radius_m > 0.0 && radius_m <= 0.01) return std::nullopt;
  return "must be in (0, 0.01] m (got " + num(radius_m) + ")";
}

}  // namespace thaw::render::media
