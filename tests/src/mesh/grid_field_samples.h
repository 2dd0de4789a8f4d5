#pragma once
// Test helper: GridFields sampled from analytic shapes (signed distance, negative inside), with
// cell volume fractions by sub-sampling, as a grid Stefan solver would write them.
#include <cmath>
#include <functional>

#include "sim/format/grid_field_file.h"

namespace thaw::mesh::testing {

using Sdf = std::function<double(double x, double y, double z)>;

/// Ice where `ice` < 0 and `cavity` >= 0; water where `cavity` < 0 (cavity inside the ice). The
/// grid spans [-half, half]^3 with cell edge h; fractions from n^3 sub-samples per cell (cells
/// farther than a cell diagonal from both surfaces take the value of their centre).
inline sim::GridField sample_cartesian(const Sdf& ice, const Sdf& cavity, double half_m, double h_m,
                                       int n = 5) {
  sim::GridField f;
  f.geometry = sim::GridField::Geometry::cartesian3d;
  const int cells = static_cast<int>(std::ceil(2 * half_m / h_m));
  f.cells = {cells, cells, cells};
  f.origin_m = {-0.5 * cells * h_m, -0.5 * cells * h_m, -0.5 * cells * h_m};
  f.spacing_m = h_m;
  const std::size_t count = f.cell_count();
  f.temperature_c.assign(count, -1.0f);
  f.ice_fraction.assign(count, 0.0f);
  f.water_fraction.assign(count, 0.0f);
  const double reach = std::sqrt(3.0) * h_m;
  for (int k = 0; k < cells; ++k)
    for (int j = 0; j < cells; ++j)
      for (int i = 0; i < cells; ++i) {
        const double cx = f.origin_m[0] + (i + 0.5) * h_m, cy = f.origin_m[1] + (j + 0.5) * h_m,
                     cz = f.origin_m[2] + (k + 0.5) * h_m;
        const double di = ice(cx, cy, cz), dc = cavity ? cavity(cx, cy, cz) : 1.0;
        double fi = 0, fw = 0;
        if (std::abs(di) > reach && std::abs(dc) > reach) {
          fw = dc < 0 ? 1 : 0;
          fi = (di < 0 && dc >= 0) ? 1 : 0;
        } else {
          for (int c = 0; c < n; ++c)
            for (int b = 0; b < n; ++b)
              for (int a = 0; a < n; ++a) {
                const double x = cx + ((a + 0.5) / n - 0.5) * h_m,
                             y = cy + ((b + 0.5) / n - 0.5) * h_m,
                             z = cz + ((c + 0.5) / n - 0.5) * h_m;
                const bool in_cavity = cavity && cavity(x, y, z) < 0;
                fw += in_cavity;
                fi += !in_cavity && ice(x, y, z) < 0;
              }
          fi /= n * n * n;
          fw /= n * n * n;
        }
        f.ice_fraction[f.index(i, j, k)] = static_cast<float>(fi);
        f.water_fraction[f.index(i, j, k)] = static_cast<float>(fw);
      }
  return f;
}

/// The same for a body of revolution about the y axis, given by signed distances in (r, y); the
/// fractions are ring-volume fractions (sub-samples weighted by r).
inline sim::GridField sample_axisymmetric(const std::function<double(double r, double y)>& ice,
                                          const std::function<double(double r, double y)>& cavity,
                                          double radius_m, double half_height_m, double h_m,
                                          int n = 6) {
  sim::GridField f;
  f.geometry = sim::GridField::Geometry::axisymmetric;
  const int nr = static_cast<int>(std::ceil(radius_m / h_m)),
            ny = static_cast<int>(std::ceil(2 * half_height_m / h_m));
  f.cells = {nr, ny, 1};
  f.origin_m = {0, -0.5 * ny * h_m, 0};
  f.spacing_m = h_m;
  f.temperature_c.assign(f.cell_count(), -1.0f);
  f.ice_fraction.assign(f.cell_count(), 0.0f);
  f.water_fraction.assign(f.cell_count(), 0.0f);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nr; ++i) {
      double wi = 0, ww = 0, wsum = 0;
      for (int b = 0; b < n; ++b)
        for (int a = 0; a < n; ++a) {
          const double r = (i + (a + 0.5) / n) * h_m, y = f.origin_m[1] + (j + (b + 0.5) / n) * h_m;
          const bool in_cavity = cavity && cavity(r, y) < 0;
          ww += r * in_cavity;
          wi += r * (!in_cavity && ice(r, y) < 0);
          wsum += r;
        }
      f.ice_fraction[f.index(i, j, 0)] = static_cast<float>(wi / wsum);
      f.water_fraction[f.index(i, j, 0)] = static_cast<float>(ww / wsum);
    }
  return f;
}

/// Signed distance to an axis-aligned box of half sizes (a, b, c) with edges rounded by radius e.
inline double rounded_box(double x, double y, double z, double a, double b, double c, double e) {
  const double qx = std::abs(x) - (a - e), qy = std::abs(y) - (b - e), qz = std::abs(z) - (c - e);
  const double ox = std::max(qx, 0.0), oy = std::max(qy, 0.0), oz = std::max(qz, 0.0);
  return std::sqrt(ox * ox + oy * oy + oz * oz) + std::min(std::max(qx, std::max(qy, qz)), 0.0) - e;
}

}  // namespace thaw::mesh::testing
