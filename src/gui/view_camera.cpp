#include "src/gui/view_camera.h"

#include <cmath>
#include <numbers>

namespace thaw::gui {
namespace {

using V = std::array<double, 3>;

V add(const V& a, const V& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
V sub(const V& a, const V& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
V mul(const V& a, double s) {
  return {a[0] * s, a[1] * s, a[2] * s};
}
double dot(const V& a, const V& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
V cross(const V& a, const V& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const V& a) {
  return std::sqrt(dot(a, a));
}
V unit(const V& a) {
  const double n = norm(a);
  return n > 0 ? mul(a, 1.0 / n) : a;
}
double radians(double deg) {
  return deg * std::numbers::pi / 180.0;
}

/// `v` rotated by `deg` about the unit axis `k` (right-handed; Rodrigues' formula).
V rotate(const V& v, const V& k, double deg) {
  const double c = std::cos(radians(deg)), s = std::sin(radians(deg));
  return add(add(mul(v, c), mul(cross(k, v), s)), mul(k, dot(k, v) * (1 - c)));
}

/// The view-up made orthogonal to the direction of projection, of unit length.
V orthogonal_up(const ViewCamera& c) {
  const V dop = unit(sub(c.focal_point, c.position));
  return unit(sub(c.view_up, mul(dop, dot(c.view_up, dop))));
}

}  // namespace

ViewCamera orbit(const ViewCamera& camera, double azimuth_deg, double elevation_deg) {
  ViewCamera c = camera;
  const V& f = c.focal_point;
  c.position = add(f, rotate(sub(c.position, f), unit(c.view_up), azimuth_deg));
  // the axis to the camera's left: minus its right, (dop x up)
  const V right = unit(cross(sub(f, c.position), orthogonal_up(c)));
  c.position = add(f, rotate(sub(c.position, f), mul(right, -1.0), elevation_deg));
  c.view_up = orthogonal_up(c);
  return c;
}

ViewCamera pan(const ViewCamera& camera, double right, double up) {
  ViewCamera c = camera;
  const V to_focus = sub(c.focal_point, c.position);
  const double height = 2.0 * norm(to_focus) * std::tan(radians(0.5 * c.vertical_fov_deg));
  const V u = orthogonal_up(c);
  const V r = unit(cross(to_focus, u));
  const V move = add(mul(r, right * height), mul(u, up * height));
  c.position = add(c.position, move);
  c.focal_point = add(c.focal_point, move);
  return c;
}

ViewCamera dolly(const ViewCamera& camera, double factor) {
  ViewCamera c = camera;
  if (factor <= 0) return c;
  const V back = sub(c.position, c.focal_point);
  c.position = add(c.focal_point, mul(back, 1.0 / factor));
  return c;
}

ViewCamera frame_bounds(const ViewCamera& camera, const std::array<double, 6>& b, double aspect) {
  ViewCamera c = camera;
  const V normal = unit(sub(c.position, c.focal_point));  // VTK's view-plane normal
  const V center{0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])};
  const V size{b[1] - b[0], b[3] - b[2], b[5] - b[4]};
  double radius = 0.5 * norm(size);
  if (radius == 0) radius = 0.5;  // a single point: VTK's radius of 1 before halving
  // The sphere's tangents from the camera at the half angle (vtkRenderer::ResetCamera): the
  // vertical angle, or for a view taller than wide the horizontal one it implies.
  double angle = radians(c.vertical_fov_deg);
  if (aspect < 1.0) angle = 2.0 * std::atan(std::tan(0.5 * angle) * aspect);
  const double distance = radius / std::sin(0.5 * angle);
  if (std::abs(dot(unit(c.view_up), normal)) > 0.999)  // as VTK: an up along the view axis
    c.view_up = {-c.view_up[2], c.view_up[0], c.view_up[1]};
  c.focal_point = center;
  c.position = add(center, mul(normal, distance));
  return c;
}

}  // namespace thaw::gui
