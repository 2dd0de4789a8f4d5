#include "src/inspect/field_probe.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thaw::inspect {
namespace {

// Along one axis of n cells: the lower of the two cell centres around `u` (in cells from the
// first centre) and the weight of the upper one, both clamped into the grid.
struct Axis {
  int lower, upper;
  double upper_weight;
};

Axis axis(double u, int n) {
  if (n <= 1 || u <= 0) return {0, 0, 0.0};
  if (u >= n - 1) return {n - 1, n - 1, 0.0};
  const int i = static_cast<int>(std::floor(u));
  return {i, i + 1, u - i};
}

}  // namespace

double material_temperature_c(const sim::GridField& f, const std::array<double, 3>& p) {
  const double h = f.spacing_m;
  const bool revolved = f.geometry == sim::GridField::Geometry::axisymmetric;
  // Field coordinates: (r, y, 0) for an axisymmetric field, (x, y, z) otherwise.
  const std::array<double, 3> q =
      revolved ? std::array<double, 3>{std::hypot(p[0], p[2]), p[1], 0} : p;
  Axis a[3];
  for (int c = 0; c < 3; ++c) a[c] = axis((q[c] - f.origin_m[c]) / h - 0.5, f.cells[c]);
  double weighted = 0, weight = 0, plain = 0;
  for (int corner = 0; corner < 8; ++corner) {
    int index[3];
    double w = 1;
    for (int c = 0; c < 3; ++c) {
      const bool up = (corner >> c) & 1;
      index[c] = up ? a[c].upper : a[c].lower;
      w *= up ? a[c].upper_weight : 1 - a[c].upper_weight;
    }
    const std::size_t cell = f.index(index[0], index[1], index[2]);
    const double material = double(f.ice_fraction[cell]) + double(f.water_fraction[cell]);
    plain += w * f.temperature_c[cell];
    weighted += w * material * f.temperature_c[cell];
    weight += w * material;
  }
  if (weight > 0) return weighted / weight;
  // A vertex moved off the material by smoothing (or a sub-cell remnant): the nearest material
  // cell within two cells of the stencil, not the air's temperature.
  double best = 0, nearest = std::numeric_limits<double>::infinity();
  for (int dk = -2; dk <= 3; ++dk)
    for (int dj = -2; dj <= 3; ++dj)
      for (int di = -2; di <= 3; ++di) {
        const int i = a[0].lower + di, j = a[1].lower + dj, k = a[2].lower + dk;
        if (i < 0 || j < 0 || k < 0 || i >= f.cells[0] || j >= f.cells[1] || k >= f.cells[2])
          continue;
        const std::size_t cell = f.index(i, j, k);
        if (!(f.ice_fraction[cell] + f.water_fraction[cell] > 0)) continue;
        const double c[3] = {f.origin_m[0] + (i + 0.5) * h, f.origin_m[1] + (j + 0.5) * h,
                             f.origin_m[2] + (k + 0.5) * h};
        const double d = std::hypot(q[0] - c[0], q[1] - c[1], q[2] - c[2]);
        if (d < nearest) nearest = d, best = f.temperature_c[cell];
      }
  return std::isfinite(nearest) ? best : plain;
}

}  // namespace thaw::inspect
