#pragma once
// A linear-radiance float RGB image, row-major, row 0 at the top. Knows nothing about files.
#include <vector>

#include "render/math/color.h"

namespace thaw::render {

class Image {
 public:
  Image() = default;
  Image(int width, int height)
      : m_width(width), m_height(height), m_pixels(std::size_t(width) * height) {}

  int width() const { return m_width; }
  int height() const { return m_height; }
  Rgb& at(int x, int y) { return m_pixels[std::size_t(y) * m_width + x]; }
  const Rgb& at(int x, int y) const { return m_pixels[std::size_t(y) * m_width + x]; }
  const std::vector<Rgb>& pixels() const { return m_pixels; }

 private:
  int m_width = 0, m_height = 0;
  std::vector<Rgb> m_pixels;
};

}  // namespace thaw::render
