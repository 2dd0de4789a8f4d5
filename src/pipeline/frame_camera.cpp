#include "src/pipeline/frame_camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "base/check.h"

namespace thaw::pipeline {
namespace {

using V = std::array<double, 3>;
double dot(const V& a, const V& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

}  // namespace

Box3 shell_extent(const std::vector<sim::InterfaceRecord>& rows, const sim::ShellGeometry& g,
                  const std::array<double, 3>& center, bool rest_on_floor, double floor_y) {
  double r = 0;
  for (const auto& row : rows) r = std::max(r, row.outer_radius_m);
  // Half extents of the surface at distance r from the core (docs/mesh.md).
  V half{r, r, r};
  if (g.geometry == sim::Geometry::cylinder) half[2] += 0.5 * g.length_m;
  if (g.geometry == sim::Geometry::planar)
    half[1] += 0.5 * g.lateral_size_m, half[2] += 0.5 * g.lateral_size_m;
  Box3 box;
  for (int i = 0; i < 3; ++i) box.lo[i] = center[i] - half[i], box.hi[i] = center[i] + half[i];
  if (rest_on_floor) box.lo[1] = floor_y, box.hi[1] = floor_y + 2 * half[1];
  return box;
}

render::CameraDescription framing_camera(const Box3& box, double aspect,
                                         const AutoCameraSettings& s) {
  THAW_CHECK(aspect > 0 && s.fill > 0 && s.fill <= 1, "aspect and fill must be positive");
  constexpr double deg = std::numbers::pi / 180.0;
  const double el = s.elevation_deg * deg, az = s.azimuth_deg * deg;
  // forward points from the camera to the target; right and up complete the camera's basis
  const V forward{-std::cos(el) * std::sin(az), -std::sin(el), -std::cos(el) * std::cos(az)};
  const V right{std::cos(az), 0.0, -std::sin(az)};
  const V up{-std::sin(el) * std::sin(az), std::cos(el), -std::sin(el) * std::cos(az)};
  const V target{0.5 * (box.lo[0] + box.hi[0]), 0.5 * (box.lo[1] + box.hi[1]),
                 0.5 * (box.lo[2] + box.hi[2])};
  const double tan_v = std::tan(0.5 * s.vertical_fov_deg * deg) * s.fill, tan_h = tan_v * aspect;
  // A corner at (x, y, z) in the camera basis (z along forward, from the target) is in frame
  // when |x| <= tan_h (D + z) and |y| <= tan_v (D + z): D >= |x| / tan_h - z, |y| / tan_v - z.
  double distance = 0;
  for (int c = 0; c < 8; ++c) {
    const V p{(c & 1 ? box.hi[0] : box.lo[0]) - target[0],
              (c & 2 ? box.hi[1] : box.lo[1]) - target[1],
              (c & 4 ? box.hi[2] : box.lo[2]) - target[2]};
    const double x = dot(p, right), y = dot(p, up), z = dot(p, forward);
    distance = std::max({distance, std::abs(x) / tan_h - z, std::abs(y) / tan_v - z});
  }
  render::CameraDescription cam;
  for (int i = 0; i < 3; ++i)
    cam.position[i] = target[i] - distance * forward[i], cam.look_at[i] = target[i];
  cam.up = {0.0, 1.0, 0.0};
  cam.vertical_fov_deg = s.vertical_fov_deg;
  return cam;
}

render::CameraDescription run_camera(const RunScenario& sc,
                                     const std::vector<sim::InterfaceRecord>& rows,
                                     const sim::ShellGeometry& geometry) {
  if (sc.camera_set) return sc.scene.camera;
  return framing_camera(
      shell_extent(rows, geometry, sc.shell.center, sc.shell.rest_on_floor, sc.shell.floor_y),
      static_cast<double>(sc.scene.image.width) / sc.scene.image.height);
}

}  // namespace thaw::pipeline
