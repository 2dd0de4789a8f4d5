#pragma once
// The simulated-time caption stamped on every film frame ("t = 12 min 30 s"): anti-aliased
// TrueType text (caption_font.h) on a translucent dark box in the top-left corner, or the
// built-in 5x7 bitmap font when no font file can be used. Works on any row-major linear RGB
// float buffer; knows nothing of the renderer's image type.
#include <string>

namespace thaw::pipeline {

class CaptionFont;

/// "t = 0 s", "t = 45 s", "t = 12 min 30 s", "t = 1 h 02 min" (seconds rounded).
std::string format_sim_time_label(double time_s);

/// Pixel width of `text` at `scale` (each glyph is 5x7 cells plus one cell spacing).
int label_width_px(const std::string& text, int scale);

/// Draws `text` with its top-left corner at (x, y) onto `rgb` (width*height*3 floats, row-major,
/// linear), white glyphs on a translucent dark box for legibility on any background.
/// Characters without a glyph are drawn as blanks; pixels outside the image are skipped.
void stamp_label(float* rgb, int width, int height, int x, int y, const std::string& text,
                 int scale);

/// Stamps `text` in the image's top-left corner, sized to the image (a line of height / 24, at
/// least 9 pixels), white on a box that darkens what is behind it to 35 %; with `font` null the
/// bitmap font of stamp_label() is used.
void stamp_caption(float* rgb, int width, int height, const std::string& text,
                   const CaptionFont* font);

}  // namespace thaw::pipeline
