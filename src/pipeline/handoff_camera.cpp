#include "src/pipeline/handoff_camera.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "base/check.h"
#include "render/scene/camera.h"

namespace thaw::pipeline {
namespace {

using V = std::array<double, 3>;
V sub(const V& a, const V& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const V& a, const V& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
V cross(const V& a, const V& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
V normalize(const V& a) {
  const double l = std::sqrt(dot(a, a));
  return {a[0] / l, a[1] / l, a[2] / l};
}
Matrix4 multiply(const Matrix4& a, const Matrix4& b) {
  Matrix4 c{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) c[4 * i + j] += a[4 * i + k] * b[4 * k + j];
  return c;
}
nlohmann::json rows(const Matrix4& m) {
  nlohmann::json r = nlohmann::json::array();
  for (int i = 0; i < 4; ++i) r.push_back({m[4 * i], m[4 * i + 1], m[4 * i + 2], m[4 * i + 3]});
  return r;
}

/// Near plane of the projection [m]: only z_ndc depends on it.
constexpr double kNearM = 1e-3;

}  // namespace

CameraMatrices camera_matrices(const render::CameraDescription& c, int width, int height) {
  THAW_CHECK(width > 0 && height > 0, "image size must be positive");
  // The renderer's basis (render/scene/camera.h).
  const V forward = normalize(sub(c.look_at, c.position));
  const V right = normalize(cross(forward, c.up));
  const V up = cross(right, forward);
  CameraMatrices m;
  m.width = width, m.height = height;
  // Rows: right, up, -forward; translation -R p.
  const V axes[3] = {right, up, {-forward[0], -forward[1], -forward[2]}};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m.world_to_camera[4 * i + j] = axes[i][j];
    m.world_to_camera[4 * i + 3] = -dot(axes[i], c.position);
  }
  m.world_to_camera[15] = 1;
  const double tan_v = std::tan(0.5 * c.vertical_fov_deg * std::numbers::pi / 180.0);
  const double tan_h = tan_v * width / height;
  // Perspective with the far plane at infinity (OpenGL's form with f -> infinity):
  // x_ndc = x / (-z tan_h), y_ndc = y / (-z tan_v), z_ndc = 1 + 2 near / z.
  m.camera_to_ndc = {1 / tan_h, 0, 0, 0, 0, 1 / tan_v, 0, 0, 0, 0, -1, -2 * kNearM, 0, 0, -1, 0};
  m.world_to_ndc = multiply(m.camera_to_ndc, m.world_to_camera);
  m.vertical_fov_deg = c.vertical_fov_deg;
  m.horizontal_fov_deg = 2 * std::atan(tan_h) * 180.0 / std::numbers::pi;
  return m;
}

std::array<double, 2> project_to_pixel(const CameraMatrices& m, const std::array<double, 3>& p) {
  double h[4];
  for (int i = 0; i < 4; ++i)
    h[i] = m.world_to_ndc[4 * i] * p[0] + m.world_to_ndc[4 * i + 1] * p[1] +
           m.world_to_ndc[4 * i + 2] * p[2] + m.world_to_ndc[4 * i + 3];
  const double x = h[0] / h[3], y = h[1] / h[3];
  return {0.5 * (x + 1) * m.width, 0.5 * (1 - y) * m.height};
}

Matrix4 transposed(const Matrix4& m) {
  Matrix4 t{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) t[4 * j + i] = m[4 * i + j];
  return t;
}

std::string camera_json(const render::CameraDescription& c, int width, int height) {
  const CameraMatrices m = camera_matrices(c, width, height);
  const auto v3 = [](const V& v) { return nlohmann::json{v[0], v[1], v[2]}; };
  const render::Camera rc(render::Vec3(c.position[0], c.position[1], c.position[2]),
                          render::Vec3(c.look_at[0], c.look_at[1], c.look_at[2]),
                          render::Vec3(c.up[0], c.up[1], c.up[2]), c.vertical_fov_deg, width,
                          height);
  nlohmann::json corners = nlohmann::json::array();
  const double xy[4][2] = {
      {0, 0}, {double(width), 0}, {0, double(height)}, {double(width), double(height)}};
  for (const auto& [x, y] : xy) {
    const render::Ray ray = rc.generate(static_cast<float>(x), static_cast<float>(y));
    corners.push_back({{"pixel", {x, y}},
                       {"world_m",
                        {c.position[0] + ray.direction.x, c.position[1] + ray.direction.y,
                         c.position[2] + ray.direction.z}}});
  }
  nlohmann::json j;
  j["format"] = "thaw-camera/1";
  j["position_m"] = v3(c.position);
  j["look_at_m"] = v3(c.look_at);
  j["up"] = v3(c.up);
  j["vertical_fov_deg"] = m.vertical_fov_deg;
  j["horizontal_fov_deg"] = m.horizontal_fov_deg;
  j["width_px"] = width;
  j["height_px"] = height;
  j["world"] = "metres, right-handed, +y up";
  j["camera_space"] = "x right, y up, looking along -z (OpenGL, Blender, ParaView)";
  j["ndc"] =
      "x, y in [-1, 1] across the image after division by w, y = +1 at the top edge; z = -1 at "
      "the near plane (1 mm), +1 at infinity";
  j["pixels"] =
      "px = (x_ndc + 1) / 2 * width_px, py = (1 - y_ndc) / 2 * height_px, (0, 0) the "
      "top-left corner";
  j["matrices"] = "rows of 4 x 4 matrices acting on column vectors [x, y, z, 1]";
  j["world_to_camera"] = rows(m.world_to_camera);
  j["camera_to_ndc"] = rows(m.camera_to_ndc);
  j["world_to_ndc"] = rows(m.world_to_ndc);
  j["corner_points"] = corners;
  return j.dump(2) + "\n";
}

}  // namespace thaw::pipeline
