// Tests render/image/image_io.h: the sRGB curve, PNG and PFM bytes, atomic writes.
#include "render/image/image_io.h"

#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <unistd.h>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "base/error.h"

namespace thaw::render {
namespace {

TEST(ImageIo, SrgbCurveKnownValues) {
  EXPECT_EQ(to_srgb8(0.0f), 0);
  EXPECT_EQ(to_srgb8(1.0f), 255);
  EXPECT_EQ(to_srgb8(2.0f), 255);  // clamped
  EXPECT_EQ(to_srgb8(-1.0f), 0);
  EXPECT_EQ(to_srgb8(0.5f), 188);         // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 187.5 -> 188
  EXPECT_EQ(to_srgb8(0.18f), 118);        // 18 % grey: 0.4614 -> 117.7
  EXPECT_EQ(to_srgb8(0.25f, 2.0f), 188);  // exposure +1 stop
  EXPECT_EQ(to_srgb8(0.002f), 7);         // linear segment: 12.92 * 0.002 = 0.02584 -> 6.6
}

TEST(ImageIo, PfmLayout) {
  Image img(3, 2);
  img.at(0, 0) = Rgb{1, 2, 3};  // top-left: written in the last row
  img.at(2, 1) = Rgb{4, 5, 6};  // bottom-right: written in the first row
  const std::string pfm = encode_pfm(img);
  const std::string header = "PF\n3 2\n-1.0\n";
  ASSERT_EQ(pfm.size(), header.size() + 3 * 2 * 12);
  EXPECT_EQ(pfm.substr(0, header.size()), header);
  float v[3];
  std::memcpy(v, pfm.data() + header.size() + 2 * 12, 12);
  EXPECT_EQ(v[0], 4.0f);
  std::memcpy(v, pfm.data() + header.size() + 3 * 12, 12);
  EXPECT_EQ(v[2], 3.0f);
}

TEST(ImageIo, PngSignature) {
  const std::string png = encode_png(Image(4, 4));
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

/// The exact sRGB curve (IEC 61966-2-1) in double, the reference the encoders are checked against.
double srgb_exact(double v) {
  v = std::clamp(v, 0.0, 1.0);
  return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

TEST(ImageIo, SixteenBitPngReadsBackWithinQuantisation) {
  // A ramp over [0, 1.2] (the top clamps) plus values in the linear segment, written at 16 bits
  // with +1 stop of exposure and read back by stb_image's 16-bit loader. Each code must be the
  // exact sRGB value of 2 * v times 65535 to within rounding (0.5 code) plus the float
  // evaluation of the curve (pow in float: relative error ~1e-7, times 1.055, so < 2e-7 of full
  // scale, 0.013 codes): 0.52 codes. The 8-bit PNG of the same image must give the 8-bit codes
  // to_srgb8 defines, and the 16-bit codes divided by 257 must round to them within one code.
  const int w = 256, h = 3;
  Image img(w, h);
  for (int x = 0; x < w; ++x) {
    const float ramp = 0.6f * x / (w - 1);
    img.at(x, 0) = Rgb{ramp, ramp * 0.5f, ramp * 0.25f};
    img.at(x, 1) = Rgb{0.0015f * x / (w - 1), 0.0f, 1.0f};
    img.at(x, 2) = Rgb{0.3f, 0.001f * x, 0.6f * (w - 1 - x) / (w - 1)};
  }
  const double exposure = 1.0;
  const std::string png16 = encode_png(img, exposure, 16);
  const std::string png8 = encode_png(img, exposure, 8);
  int dw = 0, dh = 0, dc = 0;
  stbi_us* d16 = stbi_load_16_from_memory(reinterpret_cast<const stbi_uc*>(png16.data()),
                                          static_cast<int>(png16.size()), &dw, &dh, &dc, 3);
  ASSERT_NE(d16, nullptr);
  ASSERT_EQ(dw, w);
  ASSERT_EQ(dh, h);
  stbi_uc* d8 = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(png8.data()),
                                      static_cast<int>(png8.size()), &dw, &dh, &dc, 3);
  ASSERT_NE(d8, nullptr);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Rgb& c = img.at(x, y);
      const float v[3] = {c.r, c.g, c.b};
      for (int k = 0; k < 3; ++k) {
        const std::size_t i = (std::size_t(y) * w + x) * 3 + k;
        const double exact = 65535.0 * srgb_exact(2.0 * v[k]);
        EXPECT_NEAR(d16[i], exact, 0.52) << x << "," << y << "," << k;
        EXPECT_EQ(d8[i], to_srgb8(v[k], 2.0f));
        EXPECT_NEAR(d16[i] / 257.0, d8[i], 0.51);
      }
    }
  stbi_image_free(d16);
  stbi_image_free(d8);
}

TEST(ImageIo, PngBitDepthRule) {
  EXPECT_TRUE(valid_png_bits(8));
  EXPECT_TRUE(valid_png_bits(16));
  EXPECT_FALSE(valid_png_bits(12));
  EXPECT_FALSE(valid_png_bits(0));
}

TEST(ImageIo, WritesAtomicallyAndChecksPaths) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("thaw_image_io_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  write_image(dir / "a.png", Image(2, 2));
  write_image(dir / "a.pfm", Image(2, 2));
  EXPECT_TRUE(std::filesystem::exists(dir / "a.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "a.pfm"));
  EXPECT_THROW(write_image(dir / "a.jpg", Image(2, 2)), UserError);
  EXPECT_THROW(write_image(dir / "missing" / "a.png", Image(2, 2)), UserError);
  // Nothing but the two finished files: no temporaries left behind.
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 2);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace thaw::render

namespace thaw::render {
namespace {

TEST(ImageIo, TableEncoderAgreesWithSrgbCurveEverywhere) {
  // encode_png uses a threshold table; it must give to_srgb8's code for every value, including
  // the floats on both sides of each of the 255 rounding boundaries.
  int checked = 0;
  for (int i = -100; i <= 1100000; ++i) {
    const float v = i / 1000000.0f;
    ASSERT_EQ(srgb8_by_table(v), to_srgb8(v)) << v;
    ++checked;
  }
  for (int k = 1; k < 256; ++k) {
    // bisect for the boundary of code k and check the floats next to it
    float lo = 0.0f, hi = 1.0f;
    for (int it = 0; it < 60; ++it) {
      const float mid = 0.5f * (lo + hi);
      (to_srgb8(mid) < k ? lo : hi) = mid;
    }
    for (float v : {lo, hi, std::nextafter(lo, 0.0f), std::nextafter(hi, 1.0f)})
      ASSERT_EQ(srgb8_by_table(v), to_srgb8(v)) << v;
  }
  EXPECT_EQ(srgb8_by_table(std::nanf("")), 0);
  EXPECT_EQ(srgb8_by_table(-std::nanf("")), 0);
  EXPECT_EQ(srgb8_by_table(5.0f), 255);
  EXPECT_EQ(srgb8_by_table(std::numeric_limits<float>::infinity()), 255);
  EXPECT_EQ(srgb8_by_table(-std::numeric_limits<float>::infinity()), 0);
  EXPECT_EQ(srgb8_by_table(-0.0f), 0);
  EXPECT_EQ(srgb8_by_table(std::numeric_limits<float>::denorm_min()), 0);
  EXPECT_EQ(srgb8_by_table(std::numeric_limits<float>::max()), 255);
  // Float bit patterns across [0, 2] (every bucket of the table's top-16-bit index, 64 samples
  // in each at a stride coprime with its size).
  for (std::uint32_t bits = 0; bits <= 0x40000000u; bits += 1021) {
    const float v = std::bit_cast<float>(bits);
    ASSERT_EQ(srgb8_by_table(v), to_srgb8(v)) << v;
  }
  EXPECT_GT(checked, 1000000);
}

}  // namespace
}  // namespace thaw::render
