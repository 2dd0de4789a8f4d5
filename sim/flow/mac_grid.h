#pragma once
// The uniform staggered (MAC, Harlow & Welch 1965) grid of the flow solver: pressure and
// temperature at cell centres, each velocity component on the faces normal to it. Planar 2D
// (x, y; per unit depth), axisymmetric (x = radius r from the y axis, y; per radian) or 3D
// (x, y, z). The axisymmetric metric enters only through the radius weights of faces and cells
// below. Knows nothing of fluids, solvers or scenarios.
#include <array>
#include <cstddef>

namespace thaw::sim::flow {

enum class FlowGeometry { planar, axisymmetric, cartesian3d };

struct MacGrid {
  FlowGeometry geometry = FlowGeometry::planar;
  /// cells per axis {nx, ny, nz}; nz = 1 unless cartesian3d
  std::array<int, 3> n{1, 1, 1};
  /// cell edge [m]
  double h_m = 0;

  bool axisymmetric() const { return geometry == FlowGeometry::axisymmetric; }
  /// 2 (planar, axisymmetric) or 3.
  int dims() const { return geometry == FlowGeometry::cartesian3d ? 3 : 2; }
  std::size_t cell_count() const {
    return static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]) * n[2];
  }
  std::size_t cell(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(n[0]) *
               (static_cast<std::size_t>(j) + static_cast<std::size_t>(n[1]) * k);
  }
  /// Faces of component d (normal along axis d): n + e_d per axis.
  std::array<int, 3> face_dims(int d) const {
    std::array<int, 3> f = n;
    ++f[d];
    return f;
  }
  std::size_t face_count(int d) const {
    const auto f = face_dims(d);
    return static_cast<std::size_t>(f[0]) * static_cast<std::size_t>(f[1]) * f[2];
  }
  std::size_t face(int d, int i, int j, int k) const {
    const auto f = face_dims(d);
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(f[0]) *
               (static_cast<std::size_t>(j) + static_cast<std::size_t>(f[1]) * k);
  }
  /// Radius weight at the x position i h (a face or edge plane): the radius [m] when
  /// axisymmetric, else 1.
  double radius_at_plane(int i) const { return axisymmetric() ? i * h_m : 1.0; }
  /// Radius weight at the x position (i + 1/2) h (a cell centre): the radius [m] when
  /// axisymmetric, else 1.
  double radius_at_centre(int i) const { return axisymmetric() ? (i + 0.5) * h_m : 1.0; }
  /// h^(dims - 1): the face area of a unit radius weight.
  double unit_area() const { return dims() == 3 ? h_m * h_m : h_m; }
  /// Cell volume [m^2 per unit depth | m^3 per radian | m^3].
  double cell_volume(int i) const { return radius_at_centre(i) * unit_area() * h_m; }
  /// Area of a face of component d whose x index is i (a face x index for d = 0, a cell x index
  /// otherwise) [m per unit depth | m^2 per radian | m^2].
  double face_area(int d, int i) const {
    return (d == 0 ? radius_at_plane(i) : radius_at_centre(i)) * unit_area();
  }
};

}  // namespace thaw::sim::flow
