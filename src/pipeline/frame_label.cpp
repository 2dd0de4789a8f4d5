#include "src/pipeline/frame_label.h"

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "src/pipeline/caption_font.h"

namespace thaw::pipeline {

namespace {
constexpr int kGlyphW = 5, kGlyphH = 7;

// Each glyph: 7 rows, the low 5 bits of each row, most significant bit leftmost.
struct Glyph {
  char c;
  std::uint8_t rows[kGlyphH];
};
constexpr Glyph kFont[] = {
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}},
    {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}},
    {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}},
    {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}},
    {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}},
    {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'t', {0x08, 0x08, 0x1C, 0x08, 0x08, 0x09, 0x06}},
    {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}},
    {'m', {0x00, 0x00, 0x1A, 0x15, 0x15, 0x11, 0x11}},
    {'i', {0x04, 0x00, 0x0C, 0x04, 0x04, 0x04, 0x0E}},
    {'n', {0x00, 0x00, 0x16, 0x19, 0x11, 0x11, 0x11}},
    {'s', {0x00, 0x00, 0x0E, 0x10, 0x0E, 0x01, 0x1E}},
    {'h', {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x11}},
    {'d', {0x01, 0x01, 0x0D, 0x13, 0x11, 0x11, 0x0F}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}},
    {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
    {'%', {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}},
    {'/', {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}},
    {'c', {0x00, 0x00, 0x0E, 0x10, 0x10, 0x11, 0x0E}},
    {'e', {0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E}},
    {'r', {0x00, 0x00, 0x16, 0x19, 0x10, 0x10, 0x10}},
    {'o', {0x00, 0x00, 0x0E, 0x11, 0x11, 0x11, 0x0E}},
    {'a', {0x00, 0x00, 0x0E, 0x01, 0x0F, 0x11, 0x0F}},
    {'k', {0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12}},
    {'l', {0x0C, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}},
};

const Glyph* find_glyph(char c) {
  for (const Glyph& g : kFont)
    if (g.c == c) return &g;
  return nullptr;
}
}  // namespace

std::string format_sim_time_label(double time_s) {
  const long total = std::lround(time_s < 0 ? 0 : time_s);
  char buf[64];
  if (total < 60) {
    std::snprintf(buf, sizeof buf, "t = %ld s", total);
  } else if (total < 3600) {
    std::snprintf(buf, sizeof buf, "t = %ld min %02ld s", total / 60, total % 60);
  } else {
    const long minutes = (total + 30) / 60;
    std::snprintf(buf, sizeof buf, "t = %ld h %02ld min", minutes / 60, minutes % 60);
  }
  return buf;
}

int label_width_px(const std::string& text, int scale) {
  return static_cast<int>(text.size()) * (kGlyphW + 1) * scale;
}

void stamp_label(float* rgb, int width, int height, int x, int y, const std::string& text,
                 int scale) {
  if (scale < 1) scale = 1;
  const int pad = scale * 2;
  const int box_w = label_width_px(text, scale) + 2 * pad;
  const int box_h = kGlyphH * scale + 2 * pad;
  auto pixel = [&](int px, int py) -> float* {
    if (px < 0 || py < 0 || px >= width || py >= height) return nullptr;
    return rgb + (static_cast<std::size_t>(py) * width + px) * 3;
  };
  // Darken the box to 35 % so white text reads on bright ice and on dark backgrounds alike.
  for (int py = y; py < y + box_h; ++py)
    for (int px = x; px < x + box_w; ++px)
      if (float* p = pixel(px, py))
        for (int c = 0; c < 3; ++c) p[c] *= 0.35f;
  int pen_x = x + pad;
  for (char ch : text) {
    if (const Glyph* g = find_glyph(ch)) {
      for (int row = 0; row < kGlyphH; ++row)
        for (int col = 0; col < kGlyphW; ++col)
          if (g->rows[row] & (1u << (kGlyphW - 1 - col)))
            for (int sy = 0; sy < scale; ++sy)
              for (int sx = 0; sx < scale; ++sx)
                if (float* p = pixel(pen_x + col * scale + sx, y + pad + row * scale + sy))
                  p[0] = p[1] = p[2] = 1.0f;
    }
    pen_x += (kGlyphW + 1) * scale;
  }
}

void stamp_caption(float* rgb, int width, int height, const std::string& text,
                   const CaptionFont* font) {
  if (!font) {
    const int scale = std::max(1, height / 160);
    stamp_label(rgb, width, height, scale * 3, scale * 3, text, scale);
    return;
  }
  const double px = std::max(9.0, height / 24.0);
  const double pad = 0.35 * px, margin = 0.4 * px;
  const double ascent = font->ascent_px(px), descent = font->descent_px(px);
  const int x0 = static_cast<int>(margin), y0 = static_cast<int>(margin);
  const int x1 = static_cast<int>(std::ceil(margin + font->text_width_px(text, px) + 2 * pad));
  const int y1 = static_cast<int>(std::ceil(margin + ascent + descent + 2 * pad));
  for (int y = std::max(0, y0); y < std::min(height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(width, x1); ++x)
      for (int c = 0; c < 3; ++c) rgb[(static_cast<std::size_t>(y) * width + x) * 3 + c] *= 0.35f;
  font->draw(rgb, width, height, x0 + pad, y0 + pad + ascent, text, px);
}

}  // namespace thaw::pipeline
