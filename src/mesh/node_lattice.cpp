#include "src/mesh/node_lattice.h"

#include <algorithm>
#include <cmath>

#include "base/check.h"

namespace thaw::mesh {

namespace {
// Cell-centred value of an axisymmetric field at radius r and height index j, bilinear in r
// between cell centres r_i = (i + 1/2) h. The axis is a symmetry line (cell -1 mirrors cell 0);
// beyond the last cell centre the value falls linearly to 0 (air) at the next one.
float radial_sample(const sim::GridField& f, const std::vector<float>& v, double r, int j) {
  const int nr = f.cells[0];
  const double x = r / f.spacing_m - 0.5;
  const int i0 = static_cast<int>(std::floor(x));
  const double t = x - i0;
  auto at = [&](int i) -> double {
    if (i < 0) i = -1 - i;
    return i < nr ? v[f.index(i, j, 0)] : 0.0;
  };
  return static_cast<float>((1 - t) * at(i0) + t * at(i0 + 1));
}
}  // namespace

NodeLattice NodeLattice::sample(const sim::GridField& f, const std::vector<float>& v) {
  THAW_CHECK(f.spacing_m > 0 && v.size() == f.cell_count(), "grid field with cells and a spacing");
  NodeLattice l;
  l.m_spacing = f.spacing_m;
  const double h = f.spacing_m;
  if (f.geometry == sim::GridField::Geometry::cartesian3d) {
    for (int a = 0; a < 3; ++a) {
      l.m_nodes[a] = f.cells[a] + 2;  // one layer of air nodes each side
      l.m_origin[a] = f.origin_m[a] + 0.5 * h - h;
    }
    l.m_values.assign(static_cast<std::size_t>(l.m_nodes[0]) * l.m_nodes[1] * l.m_nodes[2], 0.0f);
    for (int k = 0; k < f.cells[2]; ++k)
      for (int j = 0; j < f.cells[1]; ++j)
        for (int i = 0; i < f.cells[0]; ++i)
          l.m_values[l.index(i + 1, j + 1, k + 1)] = v[f.index(i, j, k)];
    return l;
  }
  // Axisymmetric: x and z span [-R, R] with R = nr h (nodes at half-integer multiples of h, so
  // none lies on the axis), plus the air layer.
  const int nr = f.cells[0], ny = f.cells[1];
  const int nxz = 2 * nr + 2;
  l.m_nodes = {nxz, ny + 2, nxz};
  l.m_origin = {-(nr + 0.5) * h, f.origin_m[1] - 0.5 * h, -(nr + 0.5) * h};
  l.m_values.assign(static_cast<std::size_t>(nxz) * (ny + 2) * nxz, 0.0f);
  for (int k = 1; k < nxz - 1; ++k)
    for (int j = 1; j < ny + 1; ++j)
      for (int i = 1; i < nxz - 1; ++i) {
        const auto p = l.position(i, j, k);
        l.m_values[l.index(i, j, k)] = radial_sample(f, v, std::hypot(p[0], p[2]), j - 1);
      }
  return l;
}

NodeLattice NodeLattice::from_ice_fraction(const sim::GridField& field, int smoothing_passes) {
  NodeLattice l = sample(field, field.ice_fraction);
  for (int p = 0; p < smoothing_passes; ++p) l.smooth_once();
  return l;
}

NodeLattice NodeLattice::from_water_fraction(const sim::GridField& field) {
  return sample(field, field.water_fraction);
}

// Separable [1 2 1] / 4 along x, y, z; the outermost layer stays air (value 0).
void NodeLattice::smooth_once() {
  std::vector<float> tmp(m_values.size());
  for (int axis = 0; axis < 3; ++axis) {
    const std::size_t stride = axis == 0   ? 1
                               : axis == 1 ? static_cast<std::size_t>(m_nodes[0])
                                           : static_cast<std::size_t>(m_nodes[0]) * m_nodes[1];
    for (int k = 0; k < m_nodes[2]; ++k)
      for (int j = 0; j < m_nodes[1]; ++j)
        for (int i = 0; i < m_nodes[0]; ++i) {
          const std::size_t n = index(i, j, k);
          const int c = axis == 0 ? i : axis == 1 ? j : k;
          const bool border = i == 0 || j == 0 || k == 0 || i == m_nodes[0] - 1 ||
                              j == m_nodes[1] - 1 || k == m_nodes[2] - 1;
          if (border || c == 0 || c == m_nodes[axis] - 1) {
            tmp[n] = border ? 0.0f : m_values[n];
            continue;
          }
          tmp[n] = 0.25f * m_values[n - stride] + 0.5f * m_values[n] + 0.25f * m_values[n + stride];
        }
    m_values.swap(tmp);
  }
}

}  // namespace thaw::mesh
