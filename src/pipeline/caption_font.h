#pragma once
// A TrueType font for the film's captions, rasterised anti-aliased with stb_truetype
// (libstb-dev). The default is DejaVu Sans from Debian's fonts-dejavu-core (scripts/setup).
// Draws white text with coverage as alpha onto a row-major linear RGB float buffer; knows
// nothing of the renderer's image type or of what the text says.
#include <filesystem>
#include <memory>
#include <string>

namespace thaw::pipeline {

/// Debian's fonts-dejavu-core.
inline constexpr const char* kDefaultCaptionFont =
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

class CaptionFont {
 public:
  /// Loads a TrueType file; nullptr and `problem` set ("FILE: no such file", "FILE: not a
  /// TrueType font") if it cannot be used. Never throws for a bad file.
  static std::unique_ptr<CaptionFont> load(const std::filesystem::path& file, std::string& problem);
  ~CaptionFont();
  CaptionFont(const CaptionFont&) = delete;
  CaptionFont& operator=(const CaptionFont&) = delete;

  /// Advance width of `text` [pixels] at a line height (ascent - descent) of `pixel_height`.
  double text_width_px(const std::string& text, double pixel_height) const;
  /// Ascent above and descent below the baseline [pixels] at `pixel_height` (descent > 0).
  double ascent_px(double pixel_height) const;
  double descent_px(double pixel_height) const;
  /// Draws `text` (ASCII; other bytes are skipped) with its baseline's left end at (x, baseline)
  /// [pixels, sub-pixel positions kept], white over the buffer with the glyphs' anti-aliased
  /// coverage as alpha. Pixels outside the buffer are skipped.
  void draw(float* rgb, int width, int height, double x, double baseline, const std::string& text,
            double pixel_height) const;

 private:
  struct Impl;
  explicit CaptionFont(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> m_impl;
};

}  // namespace thaw::pipeline
