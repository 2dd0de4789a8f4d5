#pragma once
// The ice fraction of a GridField as values on a uniform lattice of nodes in 3D, the input of the
// isosurface extraction (grid_surface.h). Nodes sit at the cell centres of a 3D field; an
// axisymmetric (r, y) field is revolved about the y axis by sampling it bilinearly at
// r = hypot(x, z) on a 3D lattice of the same spacing. The lattice has one layer of air nodes
// (ice 0) all round, so every isosurface is closed, and may be smoothed with the binomial filter
// [1 2 1] / 4 along each axis (a planar volume-fraction step then crosses 0.5 closer to the true
// interface: see docs/mesh.md). Knows nothing about meshes, CGAL or files.
#include <array>
#include <cstddef>
#include <vector>

#include "sim/format/grid_field_file.h"

namespace thaw::mesh {

class NodeLattice {
 public:
  /// The lattice of `field`'s ice fraction, smoothed `smoothing_passes` times.
  static NodeLattice from_ice_fraction(const sim::GridField& field, int smoothing_passes);
  /// The lattice of `field`'s water fraction, unsmoothed (what a cavity holds).
  static NodeLattice from_water_fraction(const sim::GridField& field);

  const std::array<int, 3>& nodes() const { return m_nodes; }
  std::size_t node_count() const { return m_values.size(); }
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(m_nodes[0]) *
               (static_cast<std::size_t>(j) + static_cast<std::size_t>(m_nodes[1]) * k);
  }
  float value(std::size_t node) const { return m_values[node]; }
  float value(int i, int j, int k) const { return m_values[index(i, j, k)]; }
  /// Position of node (i, j, k) [m].
  std::array<double, 3> position(int i, int j, int k) const {
    return {m_origin[0] + i * m_spacing, m_origin[1] + j * m_spacing, m_origin[2] + k * m_spacing};
  }
  double spacing_m() const { return m_spacing; }

 private:
  static NodeLattice sample(const sim::GridField& field, const std::vector<float>& cell_values);
  void smooth_once();

  std::array<int, 3> m_nodes{0, 0, 0};
  std::array<double, 3> m_origin{0, 0, 0};  ///< position of node (0, 0, 0) [m]
  double m_spacing = 0;
  std::vector<float> m_values;
};

}  // namespace thaw::mesh
