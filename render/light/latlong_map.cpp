// Lat-long environment images; see latlong_map.h.
#include "render/light/latlong_map.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>

#include "base/check.h"

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

namespace {

/// The RGBE scanlines of a Radiance file whose header stb_image has accepted (Ward 1991,
/// "Real pixels"; the format as Radiance's own freadcolrs reads it): `file` at the start of the
/// file. Skips the header (lines up to the empty one, then the resolution line), then reads
/// h scanlines of w texels, each either "new" run-length encoded (2, 2, w >> 8, w & 255, then
/// the four byte planes in runs: a count above 128 repeats the next byte count - 128 times,
/// otherwise count literal bytes follow) or flat (4 bytes per texel). Converted as stb_image
/// does (mantissa * 2^(e - 136), 0 for e = 0), so texels are those of stbi_loadf. Unlike
/// stb_image, which feeds zeros past the end of the file (black texels for a truncated flat
/// file, an endless loop on a truncated run-length encoded one), the end of the file is an
/// error here, as is a run that overflows its scanline.
bool read_rgbe_texels(std::FILE* file, int w, int h, std::vector<Rgb>& texels,
                      std::string& problem) {
  bool ended = false;
  auto byte = [&]() -> int {
    const int c = std::getc(file);
    if (c == EOF) ended = true;
    return c == EOF ? 0 : c;
  };
  auto truncated = [&]() {
    problem = "is truncated (the file ends before its " + std::to_string(w) + " x " +
              std::to_string(h) + " texels)";
    return false;
  };
  // Header lines up to the empty one, then the resolution line.
  bool line_empty = true, resolution = false;
  for (;;) {
    const int c = byte();
    if (ended) return truncated();
    if (c != '\n') {
      line_empty = false;
      continue;
    }
    if (resolution) break;
    if (line_empty) resolution = true;
    line_empty = true;
  }
  texels.assign(static_cast<std::size_t>(w) * h, Rgb{});
  std::vector<unsigned char> line(static_cast<std::size_t>(w) * 4);
  for (int j = 0; j < h; ++j) {
    unsigned char head[4];
    for (unsigned char& c : head) c = static_cast<unsigned char>(byte());
    if (ended) return truncated();
    const bool rle = w >= 8 && w < 32768 && head[0] == 2 && head[1] == 2 && !(head[2] & 0x80);
    if (rle) {
      if (((head[2] << 8) | head[3]) != w) {
        problem = "is a damaged Radiance HDR image (scanline " + std::to_string(j) +
                  " says it is " + std::to_string((head[2] << 8) | head[3]) + " texels wide)";
        return false;
      }
      for (int k = 0; k < 4; ++k) {
        for (int i = 0; i < w;) {
          int count = byte();
          const bool run = count > 128;
          if (run) count -= 128;
          if (ended) return truncated();
          if (count == 0 || count > w - i) {
            problem = "is a damaged Radiance HDR image (bad run length in scanline " +
                      std::to_string(j) + ")";
            return false;
          }
          const int value = run ? byte() : 0;
          for (int n = 0; n < count; ++n, ++i)
            line[4 * i + k] = static_cast<unsigned char>(run ? value : byte());
          if (ended) return truncated();
        }
      }
    } else {
      std::copy(head, head + 4, line.begin());
      for (std::size_t n = 4; n < line.size(); ++n) line[n] = static_cast<unsigned char>(byte());
      if (ended) return truncated();
    }
    for (int i = 0; i < w; ++i) {
      const unsigned char* t = &line[4 * i];
      Rgb& out = texels[static_cast<std::size_t>(j) * w + i];
      if (t[3] == 0) continue;
      const float f = std::ldexp(1.0f, int(t[3]) - (128 + 8));
      out = Rgb{float(t[0]) * f, float(t[1]) * f, float(t[2]) * f};
    }
  }
  return true;
}

}  // namespace

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
  // The texels by our own reader (RGBE texels are finite and non-negative by construction:
  // at most 255 * 2^119).
  std::vector<Rgb> texels;
  std::rewind(file.get());
  if (!read_rgbe_texels(file.get(), w, h, texels, problem)) return std::nullopt;
  return LatLongMap(w, h, std::move(texels));
}

}  // namespace thaw::render
