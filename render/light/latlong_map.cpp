// Lat-long environment images; see latlong_map.h.
#include "render/light/latlong_map.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>

#include "src/common/check.h"

// stb_image's Radiance reader only, with internal linkage (tests link their own stb_image).
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_HDR
#define STBI_NO_STDIO_WARNINGS
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

namespace thaw::render {

LatLongMap::LatLongMap(int width, int height, std::vector<Rgb> texels)
    : m_width(width), m_height(height), m_texels(std::move(texels)) {
  THAW_CHECK(height >= 1 && width == 2 * height, "a lat-long map is twice as wide as high");
  THAW_CHECK(m_texels.size() == static_cast<std::size_t>(width) * height, "texel count");
}

void LatLongMap::direction_to_uv(const Vec3& d, float& u, float& v) {
  constexpr float kInvTwoPi = 0.5f / std::numbers::pi_v<float>;
  u = 0.5f + std::atan2(d.x, -d.z) * kInvTwoPi;
  v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) * std::numbers::inv_pi_v<float>;
}

Vec3 LatLongMap::uv_to_direction(float u, float v) {
  const float phi = (u - 0.5f) * 2.0f * std::numbers::pi_v<float>;
  const float theta = v * std::numbers::pi_v<float>;
  const float s = std::sin(theta);
  return {s * std::sin(phi), std::cos(theta), -s * std::cos(phi)};
}

Rgb LatLongMap::radiance(const Vec3& d) const {
  float u, v;
  direction_to_uv(d, u, v);
  // Texel centres sit at (i + 0.5) / width: interpolate between the two around x, y.
  const float x = u * float(m_width) - 0.5f, y = v * float(m_height) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  auto wrap = [&](int i) { return ((i % m_width) + m_width) % m_width; };
  const int i0 = wrap(static_cast<int>(fx)), i1 = wrap(static_cast<int>(fx) + 1);
  const int j0 = std::clamp(static_cast<int>(fy), 0, m_height - 1);
  const int j1 = std::clamp(static_cast<int>(fy) + 1, 0, m_height - 1);
  // a + (b - a) t: exactly a where b == a, so a constant map is that constant bit for bit.
  auto lerp = [](const Rgb& a, const Rgb& b, float t) {
    return Rgb{a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
  };
  return lerp(lerp(texel(i0, j0), texel(i1, j0), tx), lerp(texel(i0, j1), texel(i1, j1), tx), ty);
}

std::optional<LatLongMap> load_latlong_hdr(const std::string& path, std::string& problem) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    problem = std::filesystem::exists(path, ec) ? "is not a regular file" : "no such file";
    return std::nullopt;
  }
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                       &std::fclose);
  if (!file) {
    problem = "cannot be opened";
    return std::nullopt;
  }
  if (!stbi_is_hdr_from_file(file.get())) {
    problem = "is not a Radiance HDR image (.hdr, RGBE; starts with #?RADIANCE or #?RGBE)";
    return std::nullopt;
  }
  int w = 0, h = 0, channels = 0;
  // Header first: an absurd size is refused before any texel is allocated.
  if (!stbi_info_from_file(file.get(), &w, &h, &channels)) {
    problem = std::string("is a damaged Radiance HDR image (") + stbi_failure_reason() + ")";
    return std::nullopt;
  }
  if (w != 2 * h || w < 2 || w > kMaxLatLongWidth) {
    problem = "is " + std::to_string(w) + " x " + std::to_string(h) +
              " texels; a lat-long map is twice as wide as high, 2 x 1 to " +
              std::to_string(kMaxLatLongWidth) + " x " + std::to_string(kMaxLatLongWidth / 2);
    return std::nullopt;
  }
  std::unique_ptr<float, void (*)(void*)> data(
      stbi_loadf_from_file(file.get(), &w, &h, &channels, 3), &stbi_image_free);
  if (!data) {
    problem = std::string("is a damaged Radiance HDR image (") + stbi_failure_reason() + ")";
    return std::nullopt;
  }
  std::vector<Rgb> texels(static_cast<std::size_t>(w) * h);
  for (std::size_t k = 0; k < texels.size(); ++k) {
    const float* p = data.get() + 3 * k;
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])) || p[0] < 0 ||
        p[1] < 0 || p[2] < 0) {
      problem = "has a negative or non-finite texel";
      return std::nullopt;
    }
    texels[k] = Rgb{p[0], p[1], p[2]};
  }
  return LatLongMap(w, h, std::move(texels));
}

}  // namespace thaw::render
