#include "sim/grid/body_faces.h"

#include <cmath>

namespace thaw::sim {

std::vector<std::string> body_face_names(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::box:
      return {"x_min", "x_max", "y_min", "y_max", "z_min", "z_max"};
    case ShapeKind::cylinder:
      return {"top", "bottom", "side"};
    default:
      return {"surface"};
  }
}

std::uint8_t body_face_of_point(const ShapeSpec& outer, const std::array<double, 3>& p,
                                bool axisymmetric) {
  const auto& c = outer.center_m;
  if (outer.kind == ShapeKind::box) {
    int axis = 0;
    double most = -1, sign = 1;
    for (int a = 0; a < 3; ++a) {
      const double u = (p[a] - c[a]) / (0.5 * outer.size_m[a]);
      if (std::abs(u) > most) most = std::abs(u), axis = a, sign = u;
    }
    return static_cast<std::uint8_t>(2 * axis + (sign >= 0 ? 1 : 0));
  }
  if (outer.kind == ShapeKind::cylinder) {
    const double r = axisymmetric ? p[0] : std::hypot(p[0] - c[0], p[2] - c[2]);
    const double u_y = (p[1] - c[1]) / (0.5 * outer.height_m), u_r = r / outer.radius_m;
    if (std::abs(u_y) >= u_r) return u_y >= 0 ? 0 : 1;  // top, bottom
    return 2;                                           // side
  }
  return 0;
}

FaceWeights body_face_weights(ShapeKind kind, const std::array<double, 3>& n, bool axisymmetric,
                              std::uint8_t fallback) {
  FaceWeights w{};
  if (kind == ShapeKind::box) {
    const double sum = std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2]);
    if (sum > 0) {
      for (int a = 0; a < 3; ++a) w[2 * a + (n[a] >= 0 ? 1 : 0)] += std::abs(n[a]) / sum;
      return w;
    }
  } else if (kind == ShapeKind::cylinder) {
    const double across = axisymmetric ? std::abs(n[0]) : std::hypot(n[0], n[2]);
    const double sum = std::abs(n[1]) + across;
    if (sum > 0) {
      w[n[1] >= 0 ? 0 : 1] = std::abs(n[1]) / sum;
      w[2] = across / sum;
      return w;
    }
  } else {
    w[0] = 1;
    return w;
  }
  w[fallback] = 1;
  return w;
}

}  // namespace thaw::sim
