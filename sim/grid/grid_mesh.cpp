#include "sim/grid/grid_mesh.h"

#include <numbers>

#include "base/check.h"

namespace thaw::sim {

GridMesh::GridMesh(GridField::Geometry geometry, std::array<int, 3> cells,
                   std::array<double, 3> origin, double dx)
    : nx(cells[0]),
      ny(cells[1]),
      nz(cells[2]),
      n(static_cast<long>(cells[0]) * cells[1] * cells[2]),
      axisymmetric(geometry == GridField::Geometry::axisymmetric),
      origin_m(origin),
      dx_m(dx) {
  THAW_CHECK(nx > 0 && ny > 0 && nz > 0 && dx_m > 0, "grid problem with an empty grid");
  THAW_CHECK(!axisymmetric || nz == 1, "axisymmetric grids have one cell in z");
  const double s = dx_m;
  vol.assign(static_cast<std::size_t>(n), 0.0);
  area_x.assign(static_cast<std::size_t>(nx), 0.0);
  area_y.assign(static_cast<std::size_t>(nx), 0.0);
  const double pi = std::numbers::pi;
  for (int i = 0; i < nx; ++i) {
    if (axisymmetric) {
      // Full rings about the y axis: volumes and areas of the whole revolution.
      const double r0 = i * s, r1 = (i + 1) * s;
      area_x[i] = 2 * pi * r1 * s;
      area_y[i] = pi * (r1 * r1 - r0 * r0);
    } else {
      area_x[i] = s * s;
      area_y[i] = s * s;
    }
  }
  area_z = s * s;
  for (long c = 0; c < n; ++c) vol[c] = area_y[c % nx] * s;
}

std::array<double, 3> GridMesh::centre(long c) const {
  const double s = dx_m;
  const int i = static_cast<int>(c % nx), j = static_cast<int>((c / nx) % ny),
            k = static_cast<int>(c / (static_cast<long>(nx) * ny));
  return {origin_m[0] + (i + 0.5) * s, origin_m[1] + (j + 0.5) * s,
          axisymmetric ? 0.0 : origin_m[2] + (k + 0.5) * s};
}

}  // namespace thaw::sim
