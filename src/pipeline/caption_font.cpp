#include "src/pipeline/caption_font.h"

#include <stb/stb_truetype.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <vector>

namespace thaw::pipeline {

struct CaptionFont::Impl {
  std::vector<unsigned char> data;  ///< the file; stb_truetype reads it in place
  stbtt_fontinfo info{};
  /// stb's scale for a line height (ascent - descent) of one pixel
  double scale_per_px = 0;
  int ascent = 0, descent = 0;
};

CaptionFont::CaptionFont(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
CaptionFont::~CaptionFont() = default;

std::unique_ptr<CaptionFont> CaptionFont::load(const std::filesystem::path& file,
                                               std::string& problem) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    problem = file.string() + ": no such file (install fonts-dejavu-core)";
    return nullptr;
  }
  auto impl = std::make_unique<Impl>();
  impl->data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  // A TrueType / OpenType header is at least 12 bytes; stb checks the tag and the tables.
  const int offset =
      impl->data.size() >= 12 ? stbtt_GetFontOffsetForIndex(impl->data.data(), 0) : -1;
  if (offset < 0 || !stbtt_InitFont(&impl->info, impl->data.data(), offset)) {
    problem = file.string() + ": not a TrueType font";
    return nullptr;
  }
  int line_gap = 0;
  stbtt_GetFontVMetrics(&impl->info, &impl->ascent, &impl->descent, &line_gap);
  impl->scale_per_px = stbtt_ScaleForPixelHeight(&impl->info, 1.0f);
  return std::unique_ptr<CaptionFont>(new CaptionFont(std::move(impl)));
}

double CaptionFont::ascent_px(double px) const {
  return m_impl->ascent * m_impl->scale_per_px * px;
}
double CaptionFont::descent_px(double px) const {
  return -m_impl->descent * m_impl->scale_per_px * px;
}

double CaptionFont::text_width_px(const std::string& text, double px) const {
  const double scale = m_impl->scale_per_px * px;
  double width = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    int advance = 0, bearing = 0;
    stbtt_GetCodepointHMetrics(&m_impl->info, static_cast<unsigned char>(text[i]), &advance,
                               &bearing);
    width += advance * scale;
    if (i + 1 < text.size())
      width +=
          scale * stbtt_GetCodepointKernAdvance(&m_impl->info, static_cast<unsigned char>(text[i]),
                                                static_cast<unsigned char>(text[i + 1]));
  }
  return width;
}

void CaptionFont::draw(float* rgb, int width, int height, double x, double baseline,
                       const std::string& text, double px) const {
  const float scale = static_cast<float>(m_impl->scale_per_px * px);
  const int base_y = static_cast<int>(std::floor(baseline));
  const float shift_y = static_cast<float>(baseline - base_y);
  double pen = x;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const int c = static_cast<unsigned char>(text[i]);
    if (c >= 128) continue;
    const int pen_x = static_cast<int>(std::floor(pen));
    const float shift_x = static_cast<float>(pen - pen_x);
    int w = 0, h = 0, xoff = 0, yoff = 0;
    // Coverage of the glyph at its sub-pixel offset: anti-aliased by stb's exact area coverage.
    unsigned char* bitmap = stbtt_GetCodepointBitmapSubpixel(&m_impl->info, scale, scale, shift_x,
                                                             shift_y, c, &w, &h, &xoff, &yoff);
    for (int row = 0; row < h; ++row)
      for (int col = 0; col < w; ++col) {
        const int px_x = pen_x + xoff + col, px_y = base_y + yoff + row;
        if (px_x < 0 || px_y < 0 || px_x >= width || px_y >= height) continue;
        const float alpha = bitmap[row * w + col] / 255.0f;
        float* p = rgb + (static_cast<std::size_t>(px_y) * width + px_x) * 3;
        for (int k = 0; k < 3; ++k) p[k] = p[k] * (1 - alpha) + alpha;
      }
    stbtt_FreeBitmap(bitmap, nullptr);
    int advance = 0, bearing = 0;
    stbtt_GetCodepointHMetrics(&m_impl->info, c, &advance, &bearing);
    pen += advance * scale;
    if (i + 1 < text.size())
      pen += scale * stbtt_GetCodepointKernAdvance(&m_impl->info, c,
                                                   static_cast<unsigned char>(text[i + 1]));
  }
}

}  // namespace thaw::pipeline
