// Lat-long environment images from OpenEXR files; see latlong_map.h.
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
    Imf::RgbaInputFile file(path.c_str());
    const Imath::Box2i dw = file.dataWindow();
    const long long w = static_cast<long long>(dw.max.x) - dw.min.x + 1;
    const long long h = static_cast<long long>(dw.max.y) - dw.min.y + 1;
    // The size first: an absurd one is refused before any texel is allocated.
    if (w != 2 * h || w < 2 || w > kMaxLatLongWidth) {
      problem = "is " + std::to_string(w) + " x " + std::to_string(h) +
                " texels; a lat-long map is twice as wide as high, 2 x 1 to " +
                std::to_string(kMaxLatLongWidth) + " x " + std::to_string(kMaxLatLongWidth / 2);
      return std::nullopt;
    }
    std::vector<Imf::Rgba> pixels(static_cast<std::size_t>(w * h));
    file.setFrameBuffer(pixels.data() - dw.min.x - static_cast<std::ptrdiff_t>(dw.min.y) * w, 1,
                        static_cast<std::size_t>(w));
    // Throws on a truncated or damaged file (OpenEXR checks every chunk it reads).
    file.readPixels(dw.min.y, dw.max.y);
    std::vector<Rgb> texels(pixels.size());
    for (std::size_t k = 0; k < pixels.size(); ++k) {
      const float r = pixels[k].r, g = pixels[k].g, b = pixels[k].b;
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
