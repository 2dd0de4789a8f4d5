// Tests of src/pipeline/caption_font (and frame_label's stamp_caption): DejaVu Sans loads and
// draws anti-aliased white text inside the buffer only; a missing or bad font file is a clear
// problem, never a crash, and the caption falls back to the bitmap font.
#include "src/pipeline/caption_font.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <vector>

#include "src/pipeline/frame_label.h"

namespace thaw::pipeline {
namespace {
namespace fs = std::filesystem;

std::unique_ptr<CaptionFont> dejavu() {
  std::string problem;
  auto font = CaptionFont::load(kDefaultCaptionFont, problem);
  EXPECT_TRUE(font) << problem << " (scripts/setup installs fonts-dejavu-core)";
  return font;
}

TEST(CaptionFont, DrawsAntiAliasedWhiteTextInsideTheBufferOnly) {
  const auto font = dejavu();
  ASSERT_TRUE(font);
  const int w = 120, h = 30;
  std::vector<float> img(w * h * 3, 0.0f);
  // Partly outside on purpose: must not write out of bounds (ASan checks this).
  font->draw(img.data(), w, h, 4.3, 20.6, "t = 12 min 30 s", 18);
  font->draw(img.data(), w, h, -5, 3, "t", 18);
  int full = 0, partial = 0;
  for (int i = 0; i < w * h; ++i) {
    EXPECT_EQ(img[i * 3], img[i * 3 + 1]);  // white: grey levels only
    EXPECT_LE(img[i * 3], 1.0f);
    if (img[i * 3] >= 0.99f)
      ++full;
    else if (img[i * 3] > 0.01f)
      ++partial;
  }
  EXPECT_GT(full, 50);
  // anti-aliased: the glyphs' edges are partly covered pixels, not a hard 0/1 mask
  EXPECT_GT(partial, full / 2);
}

TEST(CaptionFont, MetricsScaleWithTheSize) {
  const auto font = dejavu();
  ASSERT_TRUE(font);
  const double w18 = font->text_width_px("t = 12 min 30 s", 18),
               w36 = font->text_width_px("t = 12 min 30 s", 36);
  EXPECT_NEAR(w36, 2 * w18, 1e-9 * w36);
  EXPECT_GT(w18, 5 * 18 * 0.3);  // 15 characters of roughly half the height
  EXPECT_NEAR(font->ascent_px(20) + font->descent_px(20), 20, 20 * 0x1p-22);  // stb's float scale
  EXPECT_GT(font->text_width_px("t = 10 min", 18), font->text_width_px("t = 1 min", 18));
}

TEST(CaptionFont, MissingOrBadFileIsAProblemNotACrash) {
  std::string problem;
  EXPECT_EQ(CaptionFont::load("/nonexistent/Font.ttf", problem), nullptr);
  EXPECT_NE(problem.find("/nonexistent/Font.ttf: no such file"), std::string::npos) << problem;
  const fs::path junk =
      fs::temp_directory_path() / ("thaw_not_a_font_" + std::to_string(::getpid()) + ".ttf");
  for (const std::string& bytes :
       {std::string(), std::string("hello"), std::string(4096, '\x7f')}) {
    std::ofstream(junk, std::ios::binary) << bytes;
    problem.clear();
    EXPECT_EQ(CaptionFont::load(junk, problem), nullptr) << bytes.size();
    EXPECT_NE(problem.find("not a TrueType font"), std::string::npos) << problem;
  }
  fs::remove(junk);
}

TEST(StampCaption, TrueTypeOrBitmapFallbackBothDarkenABoxAndWriteWhite) {
  const auto font = dejavu();
  const int w = 320, h = 240;
  for (const CaptionFont* f :
       {static_cast<const CaptionFont*>(font.get()), static_cast<const CaptionFont*>(nullptr)}) {
    std::vector<float> img(w * h * 3, 0.5f);
    stamp_caption(img.data(), w, h, "t = 7 min 36 s", f);
    int white = 0, darkened = 0;
    for (int i = 0; i < w * h; ++i) {
      if (img[i * 3] > 0.6f) ++white;  // only text is brighter than the grey background
      if (img[i * 3] < 0.5f) ++darkened;
    }
    EXPECT_GT(white, 40) << (f ? "truetype" : "bitmap");
    EXPECT_GT(darkened, 500) << (f ? "truetype" : "bitmap");
    // the caption stays in the top-left corner
    for (int y = h / 3; y < h; ++y) EXPECT_EQ(img[(y * w + 10) * 3], 0.5f);
  }
}

}  // namespace
}  // namespace thaw::pipeline
