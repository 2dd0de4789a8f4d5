#include "render/image/image_io.h"

#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "src/common/atomic_file.h"
#include "src/common/error.h"

namespace thaw::render {

float linear_to_srgb(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

std::uint8_t to_srgb8(float v, float scale) {
  if (!(v == v)) v = 0.0f;  // NaN -> black (never expected; keeps the encoder total)
  return static_cast<std::uint8_t>(std::lround(linear_to_srgb(v * scale) * 255.0f));
}

std::string encode_png(const Image& image, double exposure) {
  const float scale = static_cast<float>(std::exp2(exposure));
  const int w = image.width(), h = image.height();
  // A 4096-entry table would be faster, but exact rounding per pixel costs < 10 ms for 4 Mpixel.
  std::vector<std::uint8_t> rgb(std::size_t(w) * h * 3);
  for (std::size_t i = 0; i < image.pixels().size(); ++i) {
    const Rgb& c = image.pixels()[i];
    rgb[3 * i] = to_srgb8(c.r, scale);
    rgb[3 * i + 1] = to_srgb8(c.g, scale);
    rgb[3 * i + 2] = to_srgb8(c.b, scale);
  }
  std::string out;
  auto sink = [](void* ctx, void* data, int size) {
    static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(sink, &out, w, h, 3, rgb.data(), w * 3))
    throw UserError("", "", "PNG encoding failed");
  return out;
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

void write_png(const std::filesystem::path& path, const Image& image, double exposure) {
  write_file_atomic(path, encode_png(image, exposure));
}

void write_pfm(const std::filesystem::path& path, const Image& image) {
  write_file_atomic(path, encode_pfm(image));
}

namespace {
std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}
}  // namespace

void check_output_path(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".png" && ext != ".pfm")
    throw UserError(path.string(), "", "unsupported output format '" + ext + "' (expected .png or .pfm)");
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw UserError(path.string(), "", "output folder '" + dir.string() + "' does not exist");
  if (std::filesystem::is_directory(path, ec)) throw UserError(path.string(), "", "is a directory");
}

void write_image(const std::filesystem::path& path, const Image& image, double exposure) {
  check_output_path(path);
  if (lower_extension(path) == ".pfm")
    write_pfm(path, image);
  else
    write_png(path, image, exposure);
}

}  // namespace thaw::render
