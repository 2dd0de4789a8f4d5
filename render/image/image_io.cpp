#include "render/image/image_io.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "base/atomic_file.h"
#include "base/check.h"
#include "base/error.h"
#include "base/output_file.h"
#include "render/image/exr_io.h"
#include "render/image/png_encoder.h"

namespace thaw::render {

float linear_to_srgb(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

std::uint8_t to_srgb8(float v, float scale) {
  if (!(v == v)) v = 0.0f;  // NaN -> black (never expected; keeps the encoder total)
  return static_cast<std::uint8_t>(std::lround(linear_to_srgb(v * scale) * 255.0f));
}

namespace {

/// The same mapping as to_srgb8 without a pow per channel: thresholds[k] is the smallest linear
/// value that to_srgb8 maps to k + 1 or more (found by bisection on to_srgb8 itself, so the two
/// agree exactly), and a value's code is the number of thresholds it reaches. To find it fast, a
/// table indexed by the float's top 16 bits (sign, exponent, 7 mantissa bits) holds the code of
/// the smallest value with those bits; the few thresholds inside that bucket (a 2^-7 relative
/// range, where codes are at least 0.4 % apart) are then stepped over. Negative and NaN buckets
/// start at code 0 and never pass a threshold; +inf starts at 255.
class SrgbEncoder {
 public:
  SrgbEncoder() {
    for (int k = 0; k < 255; ++k) {
      float lo = 0.0f, hi = 1.0f;  // to_srgb8(lo) <= k < to_srgb8(hi)
      for (int it = 0; it < 40; ++it) {
        const float mid = 0.5f * (lo + hi);
        if (mid == lo || mid == hi) break;
        (to_srgb8(mid) <= k ? lo : hi) = mid;
      }
      m_thresholds[k] = hi;
    }
    for (std::uint32_t i = 0; i < 65536; ++i) {
      const float v = std::bit_cast<float>(i << 16);
      m_bucket_start[i] = v == v ? by_search(v) : 0;
    }
  }
  std::uint8_t operator()(float v) const {
    int k = m_bucket_start[std::bit_cast<std::uint32_t>(v) >> 16];
    while (k < 255 && v >= m_thresholds[k]) ++k;
    return static_cast<std::uint8_t>(k);
  }

 private:
  /// Binary search over the 255 sorted thresholds (v not NaN).
  std::uint8_t by_search(float v) const {
    int k = 0;
    for (int step = 128; step > 0; step /= 2)
      if (k + step <= 255 && v >= m_thresholds[k + step - 1]) k += step;
    return static_cast<std::uint8_t>(k);
  }

  float m_thresholds[255];
  std::uint8_t m_bucket_start[65536];
};

const SrgbEncoder& srgb_encoder() {
  static const SrgbEncoder encoder;  // built once, thread-safe (magic static)
  return encoder;
}

}  // namespace

std::uint8_t srgb8_by_table(float v) {
  return srgb_encoder()(v);
}

std::uint16_t to_srgb16(float v, float scale) {
  if (!(v == v)) v = 0.0f;
  return static_cast<std::uint16_t>(std::lround(linear_to_srgb(v * scale) * 65535.0f));
}

bool valid_png_bits(int bits) {
  return bits == 8 || bits == 16;
}

std::string encode_png(const Image& image, double exposure, int bits, ViewTransform view) {
  THAW_CHECK(valid_png_bits(bits), "PNG bit depth must be 8 or 16");
  if (view == ViewTransform::agx) {
    // The view transform first (exposure inside it), then the same sRGB encoders as clip.
    const float s = static_cast<float>(std::exp2(exposure));
    Image display(image.width(), image.height(), Image::ForOverwrite{});
#pragma omp parallel for schedule(static)
    for (int y = 0; y < image.height(); ++y)
      for (int x = 0; x < image.width(); ++x) display.at(x, y) = agx_view(image.at(x, y) * s);
    return encode_png(display, 0.0, bits, ViewTransform::clip);
  }
  const float scale = static_cast<float>(std::exp2(exposure));
  const auto n = static_cast<std::int64_t>(image.pixels().size());
  const PngLayout layout{image.width(), image.height(), 3, bits};
  if (bits == 16) {
    // Unset until the loop below writes every sample (in parallel: no serial zeroing first).
    std::vector<std::uint16_t, UninitialisedAllocator<std::uint16_t>> rgb(std::size_t(n) * 3);
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) {
      const Rgb& c = image.pixels()[static_cast<std::size_t>(i)];
      rgb[3 * i] = to_srgb16(c.r, scale);
      rgb[3 * i + 1] = to_srgb16(c.g, scale);
      rgb[3 * i + 2] = to_srgb16(c.b, scale);
    }
    return encode_png_samples(rgb.data(), layout);
  }
  const SrgbEncoder& encode = srgb_encoder();
  std::vector<std::uint8_t, UninitialisedAllocator<std::uint8_t>> rgb(std::size_t(n) * 3);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    const Rgb& c = image.pixels()[static_cast<std::size_t>(i)];
    rgb[3 * i] = encode(c.r * scale);
    rgb[3 * i + 1] = encode(c.g * scale);
    rgb[3 * i + 2] = encode(c.b * scale);
  }
  return encode_png_samples(rgb.data(), layout);
}

std::string encode_pfm(const Image& image) {
  const int w = image.width(), h = image.height();
  std::string out = "PF\n" + std::to_string(w) + " " + std::to_string(h) + "\n-1.0\n";
  const std::size_t header = out.size();
  out.resize(header + std::size_t(w) * h * 12);
  char* dst = out.data() + header;
  for (int y = h - 1; y >= 0; --y) {
    for (int x = 0; x < w; ++x) {
      const Rgb& c = image.at(x, y);
      const float v[3] = {c.r, c.g, c.b};
      std::memcpy(dst, v, 12);  // little endian on every platform thaw builds on (x86-64, arm64)
      dst += 12;
    }
  }
  return out;
}

void write_png(const std::filesystem::path& path, const Image& image, double exposure, int bits,
               ViewTransform view) {
  write_file_atomic(path, encode_png(image, exposure, bits, view));
}

void write_pfm(const std::filesystem::path& path, const Image& image) {
  write_file_atomic(path, encode_pfm(image));
}

bool is_exr_path(const std::filesystem::path& path) {
  return lower_extension(path) == ".exr";
}

void check_output_path(const std::filesystem::path& path) {
  check_output_file(path, {".png", ".pfm", ".exr"});  // base/output_file.h
  const std::filesystem::path dir =
      path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw UserError(path.string(), "", "output folder '" + dir.string() + "' does not exist");
}

void write_image(const std::filesystem::path& path, const Image& image, double exposure,
                 int png_bits, ViewTransform view) {
  check_output_path(path);
  if (lower_extension(path) == ".pfm")
    write_pfm(path, image);
  else if (is_exr_path(path))
    write_exr(path, image, nullptr, ExrMetadata{});
  else
    write_png(path, image, exposure, png_bits, view);
}

}  // namespace thaw::render
