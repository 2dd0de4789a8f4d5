// Tests render/film/view_transform.h: AgX keeps grey grey, is strictly increasing from black to
// far above white, does not clip highlights (1x to 16x white keep distinct 8-bit codes below
// 255, where "clip" maps them all to 255), maps black to black and middle grey near the middle,
// and desaturates a bright pure colour towards white as film does.
#include "render/film/view_transform.h"

#include <gtest/gtest.h>

#include <cmath>

#include "render/image/image_io.h"

namespace thaw::render {
namespace {

int code8(float linear) {
  return int(std::lround(linear_to_srgb(linear) * 255.0f));
}

TEST(ViewTransform, AgxKeepsGreyGrey) {
  // The published matrices' rows sum to 1 within 1.4e-4, so a grey's channels part by a few
  // 1e-4 at most: less than half an 8-bit step on the display, where a tint would show.
  constexpr float kHalfStep = 0.5f / 255.0f;
  for (float v : {1e-3f, 0.05f, 0.18f, 1.0f, 4.0f, 30.0f}) {
    const Rgb c = agx_view(Rgb{v, v, v});
    EXPECT_NEAR(linear_to_srgb(c.r), linear_to_srgb(c.g), kHalfStep) << v;
    EXPECT_NEAR(linear_to_srgb(c.g), linear_to_srgb(c.b), kHalfStep) << v;
  }
}

TEST(ViewTransform, AgxIsIncreasingAndDoesNotClipHighlights) {
  float last = -1.0f;
  for (float ev = -12.0f; ev <= 4.0f; ev += 0.25f) {
    const float v = agx_view(Rgb{std::exp2(ev), std::exp2(ev), std::exp2(ev)}).g;
    EXPECT_GT(v, last) << ev;
    last = v;
  }
  int last_code = -1;
  for (float v : {1.0f, 2.0f, 4.0f, 8.0f, 16.0f}) {
    const int c = code8(agx_view(Rgb{v, v, v}).g);
    EXPECT_LT(c, 255) << v;
    EXPECT_GT(c, last_code) << v;
    last_code = c;
    EXPECT_EQ(code8(std::min(v, 1.0f)), 255);  // what clip does to them
  }
}

TEST(ViewTransform, AgxBlackIsBlackAndMiddleGreyIsMidTone) {
  EXPECT_EQ(code8(agx_view(Rgb{0, 0, 0}).g), 0);
  // 18 % grey lands mid-scale on the display (sRGB code between 80 and 160 of 255).
  const int grey = code8(agx_view(Rgb{0.18f, 0.18f, 0.18f}).g);
  EXPECT_GT(grey, 80);
  EXPECT_LT(grey, 160);
}

TEST(ViewTransform, AgxDesaturatesBrightColours) {
  const Rgb dim = agx_view(Rgb{0.2f, 0.0f, 0.0f}), bright = agx_view(Rgb{40.0f, 0.0f, 0.0f});
  EXPECT_GT(bright.g / bright.r, dim.g / std::max(dim.r, 1e-6f));
  EXPECT_GT(bright.g, 0.1f);
}

TEST(ViewTransform, PngUsesItAndLinearFormatsDoNot) {
  Image img(2, 1);
  img.at(0, 0) = Rgb{4.0f, 4.0f, 4.0f};
  img.at(1, 0) = Rgb{0.5f, 0.5f, 0.5f};
  EXPECT_NE(encode_png(img, 0.0, 8, ViewTransform::agx), encode_png(img, 0.0, 8));
  EXPECT_EQ(encode_png(img, 0.0, 8, ViewTransform::clip), encode_png(img, 0.0, 8));
  EXPECT_EQ(encode_pfm(img), encode_pfm(img));  // PFM has no view transform parameter at all
}

}  // namespace
}  // namespace thaw::render
