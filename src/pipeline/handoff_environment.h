#pragma once
// thaw's environment (render/light/environment.h: the sky with its panels, or a turned lat-long
// map) baked into a lat-long image in Blender's equirectangular layout, so any renderer sees the
// surround the film was rendered in. Blender's axes are z up; a thaw direction (x, y, z) is
// Blender's (x, -z, y). Blender's layout (Cycles' direction_to_equirectangular): image column u in
// [0, 1] from the left looks at azimuth atan2(y_b, x_b) = pi (1 - 2 u) (the centre along +x_b),
// row v in [0, 1] from the bottom at polar angle pi (1 - v) from +z_b. Each pixel is the mean of
// 2 x 2 directions within it (the panels' soft borders are 1-2 degrees; a 2048-pixel-wide map has
// 0.18 degree pixels). Written as a Radiance RGBE .hdr (flat scanlines), atomically.
// Knows nothing about scenes or Blender beyond the layout.
#include <array>
#include <filesystem>

#include "render/light/environment.h"

namespace thaw::pipeline {

/// The thaw direction that Blender's lat-long pixel position (u, v) in [0, 1]^2 (v from the
/// bottom) looks at.
render::Vec3 blender_latlong_direction(double u, double v);

/// Bakes `environment` as above into `path`, `width` x width / 2 pixels.
void write_environment_hdr(const render::Environment& environment,
                           const std::filesystem::path& path, int width);

}  // namespace thaw::pipeline
