#pragma once
// thaw's pinhole camera (render/scene/camera.h) as the matrices other tools take: for the EXR
// headers (OpenEXR's standard worldToCamera / worldToNDC attributes), DIR/handoff/camera.json,
// the Blender scene and the ParaView state. One convention everywhere, stated once here:
//   camera space: x right, y up, the camera looking along -z (OpenGL, Blender, ParaView), metres;
//   NDC: x_ndc, y_ndc in [-1, 1] across the image after the division by w (y_ndc = +1 at the top
//   edge), z_ndc = -1 at the near plane (1 mm) and +1 at infinity;
//   pixels: px = (x_ndc + 1) / 2 * width, py = (1 - y_ndc) / 2 * height, (0, 0) the top-left
//   corner of the image (thaw's image convention; pixel centres at half-integers).
// The basis is the renderer's (forward = look_at - position, right = forward x up, up' = right x
// forward), so a point projects to the pixel whose ray the renderer traces through it.
// Knows nothing about files or OpenEXR.
#include <array>
#include <string>

#include "render/scene/scene_description.h"

namespace thaw::pipeline {

/// Row-major 4 x 4 matrix acting on column vectors: p' = M [p, 1].
using Matrix4 = std::array<double, 16>;

struct CameraMatrices {
  Matrix4 world_to_camera{}, camera_to_ndc{}, world_to_ndc{};
  /// the full fields of view [degrees]
  double vertical_fov_deg = 0, horizontal_fov_deg = 0;
  int width = 0, height = 0;
};

/// The matrices of `camera` for an image of width x height pixels.
CameraMatrices camera_matrices(const render::CameraDescription& camera, int width, int height);

/// Where world point `p` [m] lands in the image [pixels, (0, 0) top-left], by world_to_ndc.
std::array<double, 2> project_to_pixel(const CameraMatrices& m, const std::array<double, 3>& p);

/// M transposed: the row-vector form OpenEXR's Imath::M44f uses (p' = [p, 1] M).
Matrix4 transposed(const Matrix4& m);

/// handoff/camera.json: the camera as thaw's scenario states it (position, look_at, up,
/// vertical_fov_deg), the image size, both fields of view, the three matrices (rows) and the
/// conventions above in words; `corner_points` are world points 1 m from the camera along the
/// renderer's rays through the image's four corners (top-left, top-right, bottom-left,
/// bottom-right), for checking a tool's camera against thaw's.
std::string camera_json(const render::CameraDescription& camera, int width, int height);

}  // namespace thaw::pipeline
