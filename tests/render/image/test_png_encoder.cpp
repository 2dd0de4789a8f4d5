// Tests render/image/png_encoder.h: the parallel-band PNG decodes losslessly (by stb_image, an
// independent decoder with its own inflate and CRC-free chunk walk, and by a check of every
// chunk's CRC here), for 8 and 16 bits, RGB and RGBA, one band and many, every filter exercised;
// the bytes do not depend on the thread count; each row's filter is the minimum-sum one.
#include "render/image/png_encoder.h"

#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <zlib.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace thaw::render {
namespace {

std::uint32_t be32(const std::string& s, std::size_t at) {
  return (std::uint32_t(std::uint8_t(s[at])) << 24) |
         (std::uint32_t(std::uint8_t(s[at + 1])) << 16) |
         (std::uint32_t(std::uint8_t(s[at + 2])) << 8) | std::uint32_t(std::uint8_t(s[at + 3]));
}

/// Walks the chunks, checks every CRC-32 and returns the chunk types in order.
std::vector<std::string> checked_chunks(const std::string& png) {
  std::vector<std::string> types;
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  std::size_t at = 8;
  while (at + 12 <= png.size()) {
    const std::uint32_t len = be32(png, at);
    const uLong crc = crc32(0L, reinterpret_cast<const Bytef*>(png.data() + at + 4), len + 4);
    EXPECT_EQ(be32(png, at + 8 + len), static_cast<std::uint32_t>(crc));
    types.push_back(png.substr(at + 4, 4));
    at += 12 + len;
  }
  EXPECT_EQ(at, png.size());
  return types;
}

/// Image content that makes each of the five filters the cheapest somewhere: flat areas,
/// horizontal and vertical gradients, a diagonal ramp and noise.
template <class T>
std::vector<T> test_pattern(int w, int h, int c, T max, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<T> v(std::size_t(w) * h * c);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < c; ++k) {
        const int region = (y * 5) / h;
        std::uint64_t s = 0;
        switch (region) {
          case 0:
            s = max / 3;
            break;
          case 1:
            s = std::uint64_t(x) * 977u * (k + 1);
            break;
          case 2:
            s = std::uint64_t(y) * 1231u + k;
            break;
          case 3:
            s = std::uint64_t(x + y) * 4099u;
            break;
          default:
            s = rng();
            break;
        }
        v[(std::size_t(y) * w + x) * c + k] = static_cast<T>(s % (std::uint64_t(max) + 1));
      }
  return v;
}

void expect_roundtrip8(int w, int h, int c) {
  const auto pixels = test_pattern<std::uint8_t>(w, h, c, 255, 7);
  const std::string png = encode_png_samples(pixels.data(), PngLayout{w, h, c, 8});
  const auto chunks = checked_chunks(png);
  ASSERT_GE(chunks.size(), 3u);
  EXPECT_EQ(chunks.front(), "IHDR");
  EXPECT_EQ(chunks.back(), "IEND");
  int dw = 0, dh = 0, dc = 0;
  stbi_uc* decoded = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(png.data()),
                                           static_cast<int>(png.size()), &dw, &dh, &dc, c);
  ASSERT_NE(decoded, nullptr) << stbi_failure_reason();
  EXPECT_EQ(dw, w);
  EXPECT_EQ(dh, h);
  EXPECT_EQ(dc, c);
  EXPECT_EQ(std::memcmp(decoded, pixels.data(), pixels.size()), 0);
  stbi_image_free(decoded);
}

TEST(PngEncoder, EightBitRoundTripsOneBand) {
  expect_roundtrip8(37, 23, 3);
}

TEST(PngEncoder, EightBitRoundTripsManyBands) {
  // 1000 x 3 + 1 bytes a row: 87 rows a band, so 400 rows make 5 bands
  expect_roundtrip8(1000, 400, 3);
  expect_roundtrip8(700, 300, 4);
}

TEST(PngEncoder, OnePixelAndOneRowBands) {
  expect_roundtrip8(1, 1, 3);
  // a row wider than a band: one row per band
  expect_roundtrip8(90000, 3, 3);
}

TEST(PngEncoder, SixteenBitRoundTripsBigEndian) {
  for (int c : {3, 4}) {
    const int w = 800, h = 200;  // 4801 or 6401 bytes a row: several bands
    const auto pixels = test_pattern<std::uint16_t>(w, h, c, 65535, 11);
    const std::string png = encode_png_samples(pixels.data(), PngLayout{w, h, c, 16});
    checked_chunks(png);
    EXPECT_EQ(png[24], 16);  // IHDR bit depth
    int dw = 0, dh = 0, dc = 0;
    stbi_us* decoded = stbi_load_16_from_memory(reinterpret_cast<const stbi_uc*>(png.data()),
                                                static_cast<int>(png.size()), &dw, &dh, &dc, c);
    ASSERT_NE(decoded, nullptr) << stbi_failure_reason();
    ASSERT_EQ(dw * dh, w * h);
    EXPECT_EQ(std::memcmp(decoded, pixels.data(), pixels.size() * 2), 0);
    stbi_image_free(decoded);
  }
}

TEST(PngEncoder, BytesDoNotDependOnThreadsAndAllLevelsDecode) {
  const int w = 500, h = 300;
  const auto pixels = test_pattern<std::uint8_t>(w, h, 3, 255, 3);
  const std::string one = encode_png_samples(pixels.data(), PngLayout{w, h, 3, 8}, 1);
  EXPECT_EQ(encode_png_samples(pixels.data(), PngLayout{w, h, 3, 8}, 2), one);
  EXPECT_EQ(encode_png_samples(pixels.data(), PngLayout{w, h, 3, 8}, 5), one);
  for (int level : {2, 6, 9}) {
    const std::string png = encode_png_samples(pixels.data(), PngLayout{w, h, 3, 8, level});
    int dw = 0, dh = 0, dc = 0;
    stbi_uc* decoded = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(png.data()),
                                             static_cast<int>(png.size()), &dw, &dh, &dc, 3);
    ASSERT_NE(decoded, nullptr);
    EXPECT_EQ(std::memcmp(decoded, pixels.data(), pixels.size()), 0) << "level " << level;
    stbi_image_free(decoded);
  }
}

/// The concatenated IDAT payloads inflated: the filtered rows, each led by its filter type.
std::vector<std::uint8_t> inflated_rows(const std::string& png, std::size_t expected) {
  std::string idat;
  std::size_t at = 8;
  while (at + 12 <= png.size()) {
    const std::uint32_t len = be32(png, at);
    if (png.compare(at + 4, 4, "IDAT") == 0) idat += png.substr(at + 8, len);
    at += 12 + len;
  }
  std::vector<std::uint8_t> out(expected);
  uLongf out_len = static_cast<uLongf>(out.size());
  EXPECT_EQ(uncompress(out.data(), &out_len, reinterpret_cast<const Bytef*>(idat.data()),
                       static_cast<uLong>(idat.size())),
            Z_OK);
  EXPECT_EQ(out_len, expected);
  return out;
}

TEST(PngEncoder, EachRowTakesTheFilterWithTheSmallestSumOfAbsoluteBytes) {
  // Reference straight from the PNG specification (9.2-9.4, 12.8): the five filters with the
  // branching Paeth predictor, cost = sum of |filtered byte as signed|, the first of equal
  // costs. RGB and RGBA (3 and 4 bytes a pixel), 8 and 16 bits, on the five-region pattern.
  const auto paeth = [](int a, int b, int c) {
    const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    if (pa <= pb && pa <= pc) return a;
    return pb <= pc ? b : c;
  };
  for (int bits : {8, 16}) {
    for (int c : {3, 4}) {
      const int w = 300, h = 100;
      const std::size_t bpp = std::size_t(c) * bits / 8, n = std::size_t(w) * bpp;
      std::string png;
      std::vector<std::uint8_t> raw(n * h);  // rows as PNG stores them (16-bit big-endian)
      if (bits == 8) {
        const auto px = test_pattern<std::uint8_t>(w, h, c, 255, 5);
        png = encode_png_samples(px.data(), PngLayout{w, h, c, 8});
        raw.assign(px.begin(), px.end());
      } else {
        const auto px = test_pattern<std::uint16_t>(w, h, c, 65535, 5);
        png = encode_png_samples(px.data(), PngLayout{w, h, c, 16});
        for (std::size_t i = 0; i < px.size(); ++i) {
          raw[2 * i] = static_cast<std::uint8_t>(px[i] >> 8);
          raw[2 * i + 1] = static_cast<std::uint8_t>(px[i] & 0xffu);
        }
      }
      const std::vector<std::uint8_t> coded = inflated_rows(png, (n + 1) * h);
      std::array<int, 5> used{};
      for (int y = 0; y < h; ++y) {
        std::array<std::vector<std::uint8_t>, 5> f;
        std::array<std::uint64_t, 5> cost{};
        for (std::size_t i = 0; i < n; ++i) {
          const std::uint8_t* row = raw.data() + std::size_t(y) * n;
          // the row above only where it exists (row - n before the first row is out of bounds)
          const std::uint8_t* up = y > 0 ? row - n : nullptr;
          const int x = row[i], a = i >= bpp ? row[i - bpp] : 0;
          const int b = up ? up[i] : 0, cc = up && i >= bpp ? up[i - bpp] : 0;
          const int v[5] = {x, x - a, x - b, x - (a + b) / 2, x - paeth(a, b, cc)};
          for (int k = 0; k < 5; ++k) {
            f[k].push_back(static_cast<std::uint8_t>(v[k]));
            cost[k] += std::abs(int(static_cast<std::int8_t>(v[k])));
          }
        }
        int best = 0;
        for (int k = 1; k < 5; ++k)
          if (cost[k] < cost[best]) best = k;
        const std::uint8_t* got = coded.data() + std::size_t(y) * (n + 1);
        ASSERT_EQ(got[0], best) << bits << " bits, " << c << " channels, row " << y;
        ASSERT_EQ(std::memcmp(got + 1, f[best].data(), n), 0) << "row " << y;
        ++used[best];
      }
      // Every filter's code path is taken by this pattern (else the test proves less).
      for (int k = 0; k < 5; ++k) EXPECT_GT(used[k], 0) << bits << " bits, filter " << k;
    }
  }
}

TEST(PngEncoder, FlatImageCompresses) {
  // Deflate must actually compress: a constant 1000 x 1000 image is 3 MB raw and a few KB coded.
  const std::vector<std::uint8_t> flat(std::size_t(1000) * 1000 * 3, 90);
  EXPECT_LT(encode_png_samples(flat.data(), PngLayout{1000, 1000, 3, 8}).size(), 40000u);
}

}  // namespace
}  // namespace thaw::render
