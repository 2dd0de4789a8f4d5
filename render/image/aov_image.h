#pragma once
// Per-pixel auxiliary outputs for compositing (AOVs: arbitrary output variables), row-major,
// row 0 at the top, the same size as the beauty Image. Filled by render/integrator/aov_pass.h,
// written by render/image/exr_io.h as named EXR layers. Knows nothing about scenes or files.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "render/math/vec3.h"

namespace thaw::render {

struct AovImage {
  int width = 0, height = 0;
  /// camera-space depth [m] of the first surface on the ray through the pixel centre, along the
  /// camera's view axis (not along the ray); +infinity where the ray hits nothing
  std::vector<float> depth;
  /// world-space unit shading normal there (outward for closed surfaces, as given for planes);
  /// zero where nothing is hit
  std::vector<Vec3> normal;
  /// 1 + index of the object hit (object_names[id - 1]); 0 = nothing
  std::vector<std::uint32_t> object_id;
  /// dielectric surfaces: 1 + index of the medium the camera ray enters (medium_names[id - 1]);
  /// 0 = an opaque surface or nothing
  std::vector<std::uint32_t> medium_id;
  /// the EXR's alpha: the share of the pixel covered by geometry [0, 1] where the background is
  /// black (rays that escape add nothing, so the beauty RGB is premultiplied by it, as OpenEXR
  /// expects); 1 everywhere otherwise (the background's radiance is part of the picture)
  std::vector<float> alpha;
  /// names of the ids: object labels and medium names
  std::vector<std::string> object_names, medium_names;

  AovImage() = default;
  AovImage(int w, int h)
      : width(w),
        height(h),
        depth(std::size_t(w) * h, std::numeric_limits<float>::infinity()),
        normal(std::size_t(w) * h, Vec3{0, 0, 0}),
        object_id(std::size_t(w) * h, 0),
        medium_id(std::size_t(w) * h, 0),
        alpha(std::size_t(w) * h, 1.0f) {}
};

}  // namespace thaw::render
