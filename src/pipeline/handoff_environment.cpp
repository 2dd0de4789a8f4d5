#include "src/pipeline/handoff_environment.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "base/atomic_file.h"
#include "base/check.h"

namespace thaw::pipeline {

render::Vec3 blender_latlong_direction(double u, double v) {
  const double azimuth = std::numbers::pi * (1 - 2 * u), polar = std::numbers::pi * (1 - v);
  const double xb = std::sin(polar) * std::cos(azimuth), yb = std::sin(polar) * std::sin(azimuth),
               zb = std::cos(polar);
  return render::Vec3(static_cast<float>(xb), static_cast<float>(zb), static_cast<float>(-yb));
}

void write_environment_hdr(const render::Environment& env, const std::filesystem::path& path,
                           int width) {
  THAW_CHECK(width >= 2 && width % 2 == 0, "a lat-long map needs an even width");
  const int height = width / 2;
  std::string text =
      "#?RADIANCE\n# thaw's environment, Blender's equirectangular layout\n"
      "FORMAT=32-bit_rle_rgbe\n\n-Y " +
      std::to_string(height) + " +X " + std::to_string(width) + "\n";
  const std::size_t header = text.size();
  text.resize(header + std::size_t(4) * width * height);
#pragma omp parallel for schedule(static)
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col) {
      render::Rgb sum(0.0f, 0.0f, 0.0f);
      for (int s = 0; s < 4; ++s) {
        const double u = (col + 0.25 + 0.5 * (s & 1)) / width;
        const double v = 1 - (row + 0.25 + 0.5 * (s >> 1)) / height;  // the file's top row first
        sum += env.radiance(blender_latlong_direction(u, v));
      }
      const float c[3] = {0.25f * sum.r, 0.25f * sum.g, 0.25f * sum.b};
      // RGBE (Ward, Graphics Gems II, "Real pixels"): a shared exponent and 8-bit mantissas.
      unsigned char* p =
          reinterpret_cast<unsigned char*>(&text[header + 4 * (std::size_t(row) * width + col)]);
      const float m = std::max({c[0], c[1], c[2]});
      if (!(m > 1e-32f)) {
        p[0] = p[1] = p[2] = p[3] = 0;
        continue;
      }
      int e = 0;
      const float scale = std::frexp(m, &e) * 256.0f / m;
      for (int k = 0; k < 3; ++k) p[k] = static_cast<unsigned char>(std::max(0.0f, c[k]) * scale);
      p[3] = static_cast<unsigned char>(e + 128);
    }
  write_file_atomic(path, text);
}

}  // namespace thaw::pipeline
