#pragma once
// A lat-long (equirectangular) environment image: the radiance arriving from every direction,
// stored as a width x height grid of linear RGB texels with width = 2 height. Conventions (map
// frame, +y up, right-handed):
//   u = 0.5 + atan2(d.x, -d.z) / (2 pi)   column: the image's centre faces -z, u grows towards +x
//   v = acos(d.y) / pi                    row: the top row is the zenith, the bottom the nadir
// Texel (i, j) covers u in [i, i + 1) / width and v in [j, j + 1) / height; lookups interpolate
// bilinearly between texel centres (wrapping in u, clamped in v). Knows nothing about scenes or
// rays beyond a direction; reading files is load_latlong_map()'s job (Radiance .hdr, OpenEXR .exr).
#include <optional>
#include <string>
#include <vector>

#include "render/math/color.h"
#include "render/math/vec3.h"

namespace thaw::render {

class LatLongMap {
 public:
  /// texels row by row from the top; width == 2 height >= 2 (THAW_CHECK).
  LatLongMap(int width, int height, std::vector<Rgb> texels);

  int width() const { return m_width; }
  int height() const { return m_height; }
  const Rgb& texel(int i, int j) const {
    return m_texels[static_cast<std::size_t>(j) * m_width + i];
  }

  /// (u, v) in [0, 1] of unit direction d (conventions above).
  static void direction_to_uv(const Vec3& d, float& u, float& v);
  /// The unit direction of (u, v).
  static Vec3 uv_to_direction(float u, float v);

  /// Radiance arriving from unit direction d (map frame), bilinear between texel centres.
  Rgb radiance(const Vec3& d) const;

 private:
  int m_width, m_height;
  std::vector<Rgb> m_texels;
};

/// Largest accepted side of a lat-long map [texels] (a 16k x 8k map is 1.5 GiB as floats).
inline constexpr int kMaxLatLongWidth = 16384;

/// Reads a Radiance RGBE image (.hdr, flat or run-length encoded) as a lat-long map. On failure
/// returns nullopt and sets `problem` ("no such file", "is not a Radiance HDR image", "is
/// 300 x 200 texels; a lat-long map is twice as wide as high", ...).
std::optional<LatLongMap> load_latlong_hdr(const std::string& path, std::string& problem);

/// Reads an OpenEXR image (.exr: its R, G, B channels, half or float; a missing channel reads
/// as 0) as a lat-long map (latlong_exr.cpp). On failure returns nullopt and sets `problem` (not
/// 2:1, a negative or non-finite texel, or OpenEXR's own message for a damaged or truncated file).
std::optional<LatLongMap> load_latlong_exr(const std::string& path, std::string& problem);

/// By the file name's extension: ".exr" (any case) through OpenEXR, anything else as Radiance.
std::optional<LatLongMap> load_latlong_map(const std::string& path, std::string& problem);

}  // namespace thaw::render
