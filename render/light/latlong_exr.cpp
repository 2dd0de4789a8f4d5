// Lat-long environment images from OpenEXR files; see latlong_map.h. R, G and B (or a lone
// luminance Y) are read into float slices, so a 32-bit float file keeps its full range (a sun of
// 70000, above half precision's 65504, was refused as non-finite when read through half-float
// Imf::Rgba). Only a chroma-subsampled luminance/chroma file (Y, RY, BY), which needs OpenEXR's
// RGBA conversion, is read as half floats.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfRgbaFile.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <exception>
#include <filesystem>

#include "render/light/latlong_map.h"

namespace thaw::render {

std::optional<LatLongMap> load_latlong_exr(const std::string& path, std::string& problem) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    problem = std::filesystem::exists(path, ec) ? "is not a regular file" : "no such file";
    return std::nullopt;
  }
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i dw = file.header().dataWindow();
    const long long w = static_cast<long long>(dw.max.x) - dw.min.x + 1;
    const long long h = static_cast<long long>(dw.max.y) - dw.min.y + 1;
    // The size first: an absurd one is refused before any texel is allocated.
    if (w != 2 * h || w < 2 || w > kMaxLatLongWidth) {
      problem = "is " + std::to_string(w) + " x " + std::to_string(h) +
                " texels; a lat-long map is twice as wide as high, 2 x 1 to " +
                std::to_string(kMaxLatLongWidth) + " x " + std::to_string(kMaxLatLongWidth / 2);
      return std::nullopt;
    }
    const std::size_t n = static_cast<std::size_t>(w * h);
    std::vector<float> rgb(3 * n);
    const Imf::ChannelList& channels = file.header().channels();
    const bool has_rgb =
        channels.findChannel("R") || channels.findChannel("G") || channels.findChannel("B");
    const bool luminance_only = !has_rgb && channels.findChannel("Y") &&
                                !channels.findChannel("RY") && !channels.findChannel("BY");
    if (has_rgb || luminance_only) {
      // OpenEXR addresses texel (x, y) at base + x * xStride + y * yStride, with x and y in the
      // data window; the base is moved so that the window's corner lands on rgb[0].
      const std::size_t x_stride = 3 * sizeof(float),
                        y_stride = x_stride * static_cast<std::size_t>(w);
      char* base = reinterpret_cast<char*>(rgb.data()) -
                   static_cast<std::ptrdiff_t>(dw.min.x) * x_stride -
                   static_cast<std::ptrdiff_t>(dw.min.y) * y_stride;
      Imf::FrameBuffer frame;
      const char* names[3] = {"R", "G", "B"};
      for (int c = 0; c < (luminance_only ? 1 : 3); ++c)
        frame.insert(
            luminance_only ? "Y" : names[c],
            Imf::Slice(Imf::FLOAT, base + c * sizeof(float), x_stride, y_stride, 1, 1, 0.0));
      file.setFrameBuffer(frame);
      // Throws on a truncated or damaged file (OpenEXR checks every chunk it reads).
      file.readPixels(dw.min.y, dw.max.y);
      if (luminance_only)
        for (std::size_t k = 0; k < n; ++k) rgb[3 * k + 1] = rgb[3 * k + 2] = rgb[3 * k];
    } else {
      Imf::RgbaInputFile rgba(path.c_str());
      std::vector<Imf::Rgba> pixels(n);
      rgba.setFrameBuffer(pixels.data() - dw.min.x - static_cast<std::ptrdiff_t>(dw.min.y) * w, 1,
                          static_cast<std::size_t>(w));
      rgba.readPixels(dw.min.y, dw.max.y);
      for (std::size_t k = 0; k < n; ++k) {
        rgb[3 * k] = pixels[k].r;
        rgb[3 * k + 1] = pixels[k].g;
        rgb[3 * k + 2] = pixels[k].b;
      }
    }
    std::vector<Rgb> texels(n);
    for (std::size_t k = 0; k < n; ++k) {
      const float r = rgb[3 * k], g = rgb[3 * k + 1], b = rgb[3 * k + 2];
      if (!(std::isfinite(r) && std::isfinite(g) && std::isfinite(b)) || r < 0 || g < 0 || b < 0) {
        problem = "has a negative or non-finite texel (column " + std::to_string(k % w) + ", row " +
                  std::to_string(k / w) + ")";
        return std::nullopt;
      }
      texels[k] = Rgb{r, g, b};
    }
    return LatLongMap(static_cast<int>(w), static_cast<int>(h), std::move(texels));
  } catch (const std::exception& e) {
    problem = std::string("is not a readable OpenEXR image (") + e.what() + ")";
    return std::nullopt;
  }
}

std::optional<LatLongMap> load_latlong_map(const std::string& path, std::string& problem) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".exr" ? load_latlong_exr(path, problem) : load_latlong_hdr(path, problem);
}

}  // namespace thaw::render
