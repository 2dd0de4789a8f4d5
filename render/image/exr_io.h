#pragma once
// OpenEXR output (the Academy's OpenEXR library, Debian libopenexr-dev) for compositing: the
// linear beauty image as half-float R, G, B, A, and with AOVs (render/image/aov_image.h) the
// layers Z (camera-space depth, 32-bit float: half has 11 significant bits, 6 cm steps at
// 100 m), N.X/N.Y/N.Z (world-space normal, half) and id.object/id.medium (32-bit float, exact
// integers up to 2^24: most compositors read float ids, not every one reads UINT channels).
// Names follow the OpenEXR layer convention ("layer.channel"; "Z" is the standard depth
// channel). Metadata as header attributes: thaw.sceneFile, thaw.simulatedTime_s (film frames),
// thaw.samplesPerPixel, thaw.exposure_stops (not applied: the pixels are linear radiance),
// thaw.objectIds / thaw.mediumIds (the names of ids 1, 2, ...), software ("thaw VERSION"), and
// when given the camera as OpenEXR's standard worldToCamera / worldToNDC (Imath M44f, row
// vectors: p' = [p, 1] M; the conventions are the caller's, src/pipeline/handoff_camera.h).
// ZIP compression (lossless, 16 scanlines a block). Written atomically like every image.
#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "render/image/aov_image.h"
#include "render/image/image.h"

namespace thaw::render {

struct ExrMetadata {
  /// the scene or scenario file rendered
  std::string scene_file;
  /// simulated time [s] of a film frame; unset for a plain `thaw render`
  std::optional<double> time_s;
  int samples_per_pixel = 0;
  double exposure_stops = 0.0;
  /// the camera's matrices, row-major for column vectors (p' = M [p, 1]); written transposed
  using Matrix4 = std::array<double, 16>;
  std::optional<Matrix4> world_to_camera, world_to_ndc;
};

/// EXR file bytes: `image` as half RGBA, plus the AOV layers if `aovs` is not null (then it must
/// be the image's size, and A is its alpha; without AOVs A = 1).
std::string encode_exr(const Image& image, const AovImage* aovs, const ExrMetadata& metadata);

void write_exr(const std::filesystem::path& path, const Image& image, const AovImage* aovs,
               const ExrMetadata& metadata);

}  // namespace thaw::render
