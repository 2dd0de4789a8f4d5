// Tests of src/pipeline/frame_camera: the built-in camera keeps the whole shell in frame, fills
// the frame as set (so a 1 cm drop is no speck and a 10 cm slab is not cut off), and depends
// only on the run's largest extent (one camera for every frame).
#include "src/pipeline/frame_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "render/scene/camera.h"

namespace thaw::pipeline {
namespace {

std::vector<sim::InterfaceRecord> radii(std::initializer_list<double> outer) {
  std::vector<sim::InterfaceRecord> rows;
  for (double r : outer) {
    sim::InterfaceRecord row;
    row.outer_radius_m = r;
    row.inner_radius_m = 0.5 * r;
    rows.push_back(row);
  }
  return rows;
}

/// Image position [pixels] of p through the renderer's own pinhole camera (render/scene/camera.h):
/// found by projecting onto the image plane spanned by two generated rays.
std::array<double, 2> project(const render::CameraDescription& d, int w, int h,
                              const std::array<double, 3>& p) {
  const render::Camera cam({float(d.position[0]), float(d.position[1]), float(d.position[2])},
                           {float(d.look_at[0]), float(d.look_at[1]), float(d.look_at[2])},
                           {float(d.up[0]), float(d.up[1]), float(d.up[2])}, d.vertical_fov_deg, w,
                           h);
  // Rays through the centre, one pixel right and one pixel down; at unit depth along the centre
  // ray these differ by the pixel steps.
  const render::Vec3 c = cam.generate(0.5f * w, 0.5f * h).direction;
  const render::Vec3 o = cam.position();
  const render::Vec3 q = render::Vec3{float(p[0]), float(p[1]), float(p[2])} - o;
  const auto at_unit_depth = [&](const render::Vec3& dir) { return dir / render::dot(dir, c); };
  const render::Vec3 dx = at_unit_depth(cam.generate(0.5f * w + 1, 0.5f * h).direction) - c;
  const render::Vec3 dy = at_unit_depth(cam.generate(0.5f * w, 0.5f * h + 1).direction) - c;
  const render::Vec3 qp = q / render::dot(q, c) - c;
  return {0.5 * w + render::dot(qp, dx) / render::dot(dx, dx),
          0.5 * h + render::dot(qp, dy) / render::dot(dy, dy)};
}

/// Largest share of the half-width / half-height any box corner reaches (1 = the frame's edge).
double largest_fill(const Box3& box, const render::CameraDescription& cam, int w, int h) {
  double fill = 0;
  for (int c = 0; c < 8; ++c) {
    const auto px = project(cam, w, h,
                            {c & 1 ? box.hi[0] : box.lo[0], c & 2 ? box.hi[1] : box.lo[1],
                             c & 4 ? box.hi[2] : box.lo[2]});
    fill = std::max(
        {fill, std::abs(px[0] - 0.5 * w) / (0.5 * w), std::abs(px[1] - 0.5 * h) / (0.5 * h)});
  }
  return fill;
}

TEST(FrameCamera, ExtentOfEachShapeRestingOnTheFloor) {
  const auto rows = radii({0.03, 0.025});
  const Box3 sphere =
      shell_extent(rows, {sim::Geometry::sphere, 0, 0, true}, {0.1, 5, 0}, true, 0.2);
  EXPECT_DOUBLE_EQ(sphere.lo[0], 0.07);
  EXPECT_DOUBLE_EQ(sphere.hi[0], 0.13);
  EXPECT_DOUBLE_EQ(sphere.lo[1], 0.2);
  EXPECT_DOUBLE_EQ(sphere.hi[1], 0.26);
  const Box3 capsule =
      shell_extent(rows, {sim::Geometry::cylinder, 0.06, 0, true}, {0, 0, 0}, false, 0);
  EXPECT_DOUBLE_EQ(capsule.hi[2], 0.06);
  EXPECT_DOUBLE_EQ(capsule.lo[1], -0.03);
  const Box3 slab = shell_extent(rows, {sim::Geometry::planar, 0, 0.1, false}, {0, 0, 0}, true, 0);
  EXPECT_DOUBLE_EQ(slab.hi[0], 0.03);
  EXPECT_DOUBLE_EQ(slab.hi[1], 0.16);
  EXPECT_DOUBLE_EQ(slab.hi[2], 0.08);
}

TEST(FrameCamera, WholeShellInFrameFillingTheSetShare) {
  // The three shipped kinds: a 1 cm drop, the default 3 cm sphere, the 10 cm heated slab, at
  // 640x480 and in portrait. The tightest corner sits exactly at `fill` of the frame, up to the
  // float arithmetic of the renderer's camera used to project: the pixel steps are differences of
  // float unit vectors about 1/w apart, relative error 2^-24 w = 3e-5 at w = 500 (tolerance 5e-5).
  const AutoCameraSettings settings;
  const std::vector<Box3> boxes{
      shell_extent(radii({0.01}), {sim::Geometry::sphere, 0, 0, true}, {0, 0, 0}, true, 0),
      shell_extent(radii({0.03, 0.02}), {sim::Geometry::sphere, 0, 0, true}, {0, 0, 0}, true, 0),
      shell_extent(radii({0.02}), {sim::Geometry::planar, 0, 0.1, false}, {0, 0, 0}, true, 0),
      shell_extent(radii({0.015}), {sim::Geometry::cylinder, 0.06, 0, true}, {0, 0, 0}, true, 0)};
  for (const auto& [w, h] : {std::pair{640, 480}, std::pair{300, 500}})
    for (const Box3& box : boxes) {
      const render::CameraDescription cam = framing_camera(box, double(w) / h, settings);
      EXPECT_NEAR(largest_fill(box, cam, w, h), settings.fill, 5e-5) << w << "x" << h;
      EXPECT_EQ(cam.vertical_fov_deg, settings.vertical_fov_deg);
      // looking down at the set elevation
      const double dy = cam.look_at[1] - cam.position[1];
      const double dist =
          std::hypot(cam.look_at[0] - cam.position[0], dy, cam.look_at[2] - cam.position[2]);
      EXPECT_NEAR(std::asin(-dy / dist) * 180 / std::numbers::pi, settings.elevation_deg, 1e-9);
    }
}

TEST(FrameCamera, OneCameraForTheWholeRun) {
  // Only the largest radius matters: the run's rows in any order, or only the largest, give the
  // same camera; a run that shrinks does not move it.
  const sim::ShellGeometry sphere{sim::Geometry::sphere, 0, 0, true};
  const auto cam = [&](const std::vector<sim::InterfaceRecord>& rows) {
    return framing_camera(shell_extent(rows, sphere, {0, 0, 0}, true, 0), 4.0 / 3.0);
  };
  const auto a = cam(radii({0.03, 0.028, 0.021})), b = cam(radii({0.021, 0.03})),
             c = cam(radii({0.03}));
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.position, c.position);
  EXPECT_EQ(a.look_at, c.look_at);
}

}  // namespace
}  // namespace thaw::pipeline
