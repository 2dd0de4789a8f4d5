// Tests render/light/latlong_map.h: the direction <-> (u, v) conventions (the image's centre
// faces -z, the top row is the zenith), a known texel seen in its direction, bilinear lookups,
// and reading Radiance files: flat and run-length encoded (the shipped studio map), and every
// bad file named (missing, not HDR, not 2:1, no size line, truncated: flat or run-length encoded,
// by one byte or by half, which stb_image alone would read with black texels).
#include "render/light/latlong_map.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>

#include "tests/render/test_util.h"

namespace thaw::render {
namespace {

// One folder per test and process: CTest runs these tests as concurrent processes, and a folder
// shared by name (the random seed, 0 unless shuffling) was removed by one test under another
// (LatLongMap.BadFilesAreNamed failed with "no such file" on a fresh Debian 12 root).
std::filesystem::path temp_dir() {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("thaw_latlong_" + std::to_string(::getpid()) + "_" +
                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(LatLongMap, DirectionConventions) {
  float u, v;
  LatLongMap::direction_to_uv({0, 0, -1}, u, v);  // the image's centre
  EXPECT_FLOAT_EQ(u, 0.5f);
  EXPECT_FLOAT_EQ(v, 0.5f);
  LatLongMap::direction_to_uv({1, 0, 0}, u, v);  // a quarter turn right of the centre
  EXPECT_FLOAT_EQ(u, 0.75f);
  LatLongMap::direction_to_uv({-1, 0, 0}, u, v);
  EXPECT_FLOAT_EQ(u, 0.25f);
  LatLongMap::direction_to_uv({0, 1, 0}, u, v);  // zenith: top row
  EXPECT_FLOAT_EQ(v, 0.0f);
  LatLongMap::direction_to_uv({0, -1, 0}, u, v);
  EXPECT_FLOAT_EQ(v, 1.0f);
  // Round trip over the sphere (float atan2/acos/sin/cos: a few 1e-7).
  for (float uu = 0.01f; uu < 1.0f; uu += 0.07f)
    for (float vv = 0.02f; vv < 1.0f; vv += 0.09f) {
      const Vec3 d = LatLongMap::uv_to_direction(uu, vv);
      EXPECT_NEAR(length(d), 1.0f, 1e-6f);
      LatLongMap::direction_to_uv(d, u, v);
      EXPECT_NEAR(u, uu, 2e-6f);
      EXPECT_NEAR(v, vv, 2e-6f);
    }
}

TEST(LatLongMap, KnownTexelIsSeenInItsDirection) {
  // One hot texel in an 8 x 4 map: its centre (u, v) = ((i + 0.5) / 8, (j + 0.5) / 4) is the
  // direction whose lookup returns it (bilinear weight 1, up to the float rounding of u * 8:
  // a weight of 1e-6 on neighbours of 0); halfway to the next texel centre, half of it.
  const int i = 5, j = 1;
  std::vector<Rgb> texels(32, Rgb{0, 0, 0});
  texels[j * 8 + i] = Rgb{4.0f, 2.0f, 1.0f};
  const LatLongMap map(8, 4, texels);
  const Vec3 d = LatLongMap::uv_to_direction((i + 0.5f) / 8, (j + 0.5f) / 4);
  // Texel (5, 1): 0.6875 of a turn from -z's opposite edge, 45 degrees above the horizon.
  EXPECT_NEAR(d.y, std::cos(0.375 * std::numbers::pi), 1e-6);
  EXPECT_GT(d.x, 0.0f);
  const Rgb hot = map.radiance(d);
  EXPECT_NEAR(hot.r, 4.0f, 1e-4f);
  EXPECT_NEAR(hot.b, 1.0f, 1e-4f);
  const Rgb half = map.radiance(LatLongMap::uv_to_direction((i + 1.0f) / 8, (j + 0.5f) / 4));
  EXPECT_NEAR(half.r, 2.0f, 1e-4f);
  // Wrapping: texel 0 and texel 7 meet at u = 0 (= 1), behind the viewer (+z).
  std::vector<Rgb> edge(32, Rgb{0, 0, 0});
  edge[2 * 8 + 0] = Rgb{1, 1, 1};
  const LatLongMap wrap(8, 4, edge);
  EXPECT_NEAR(wrap.radiance(LatLongMap::uv_to_direction(0.0f, 0.625f)).r, 0.5f, 1e-4f);
}

TEST(LatLongMap, ConstantMapIsExactlyConstant) {
  // The lerp a + (b - a) t returns a exactly when b == a, whatever t: a constant map is the
  // constant bit for bit (what lets it render exactly as kind = "constant").
  const LatLongMap map(16, 8, std::vector<Rgb>(128, Rgb{0.25f, 0.5f, 0.75f}));
  for (float x = -1; x <= 1; x += 0.13f)
    for (float y = -1; y <= 1; y += 0.17f) {
      const Vec3 d = normalize(Vec3{x, y, 0.3f});
      EXPECT_EQ(map.radiance(d), Rgb(0.25f, 0.5f, 0.75f));
    }
}

TEST(LatLongMap, ReadsRadianceFiles) {
  const auto dir = temp_dir();
  const std::string path = (dir / "gradient.hdr").string();
  ASSERT_TRUE(test::write_flat_hdr(path, 8, 4, [](int i, int j) {
    return RgbD{0.25 * (i + 1), 0.5, 2.0 * j};  // exact in RGBE (see write_flat_hdr)
  }));
  std::string problem;
  const auto map = load_latlong_hdr(path, problem);
  ASSERT_TRUE(map) << problem;
  EXPECT_EQ(map->width(), 8);
  EXPECT_EQ(map->height(), 4);
  EXPECT_EQ(map->texel(3, 0).r, 1.0f);
  EXPECT_EQ(map->texel(3, 2).b, 4.0f);
  EXPECT_EQ(map->texel(0, 1).g, 0.5f);
  // The shipped studio (run-length encoded, data/environments/make_studio_hdr.py): 512 x 256,
  // soft boxes brighter than 5, walls between 0.1 and 0.4.
  const auto studio = load_latlong_hdr(THAW_SOURCE_DIR "/data/environments/studio.hdr", problem);
  ASSERT_TRUE(studio) << problem;
  EXPECT_EQ(studio->width(), 512);
  float brightest = 0;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 512; ++x) brightest = std::max(brightest, studio->texel(x, y).g);
  EXPECT_GT(brightest, 5.0f);
  const Rgb behind = studio->radiance({0, 0, 1});  // the wall opposite the key box
  EXPECT_GT(behind.g, 0.1f);
  EXPECT_LT(behind.g, 0.4f);
  std::filesystem::remove_all(dir);
}

TEST(LatLongMap, BadFilesAreNamed) {
  const auto dir = temp_dir();
  std::string problem;
  EXPECT_FALSE(load_latlong_hdr((dir / "nope.hdr").string(), problem));
  EXPECT_EQ(problem, "no such file");
  EXPECT_FALSE(load_latlong_hdr(dir.string(), problem));
  EXPECT_EQ(problem, "is not a regular file");
  const std::string text = (dir / "text.hdr").string();
  std::ofstream(text) << "P3\n2 1\n255\n0 0 0 255 255 255\n";
  EXPECT_FALSE(load_latlong_hdr(text, problem));
  EXPECT_NE(problem.find("not a Radiance HDR image"), std::string::npos) << problem;
  const std::string square = (dir / "square.hdr").string();
  ASSERT_TRUE(test::write_flat_hdr(square, 4, 4, [](int, int) { return RgbD{1, 1, 1}; }));
  EXPECT_FALSE(load_latlong_hdr(square, problem));
  EXPECT_NE(problem.find("is 4 x 4 texels; a lat-long map is twice as wide as high"),
            std::string::npos)
      << problem;
  const std::string headless = (dir / "headless.hdr").string();
  std::ofstream(headless) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n";
  EXPECT_FALSE(load_latlong_hdr(headless, problem));
  EXPECT_NE(problem.find("damaged"), std::string::npos) << problem;
  // Truncated copies of a flat file and of the run-length encoded studio map: the whole file
  // loads, every shorter one is refused (by one byte: the last texel's exponent; by half).
  const std::string flat = (dir / "flat.hdr").string();
  ASSERT_TRUE(test::write_flat_hdr(flat, 8, 4, [](int, int) { return RgbD{1, 1, 1}; }));
  for (const std::string& source :
       {flat, std::string(THAW_SOURCE_DIR "/data/environments/studio.hdr")}) {
    std::ifstream in(source, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_TRUE(load_latlong_hdr(source, problem)) << problem;
    for (const std::size_t cut : {std::size_t{1}, bytes.size() / 2}) {
      const std::string cut_path = (dir / "cut.hdr").string();
      std::ofstream(cut_path, std::ios::binary) << bytes.substr(0, bytes.size() - cut);
      EXPECT_FALSE(load_latlong_hdr(cut_path, problem)) << source << " cut by " << cut;
      EXPECT_NE(problem.find("is truncated"), std::string::npos) << problem;
    }
  }
  std::filesystem::remove_all(dir);
}

/// Writes a w x h OpenEXR RGBA (half) image whose texel (i, j) is f(i, j).
template <class F>
void write_exr(const std::string& path, int w, int h, F f) {
  std::vector<Imf::Rgba> px(static_cast<std::size_t>(w) * h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const RgbD c = f(i, j);
      px[static_cast<std::size_t>(j) * w + i] = Imf::Rgba(float(c[0]), float(c[1]), float(c[2]));
    }
  Imf::RgbaOutputFile out(path.c_str(), w, h, Imf::WRITE_RGBA);
  out.setFrameBuffer(px.data(), 1, static_cast<std::size_t>(w));
  out.writePixels(h);
}

TEST(LatLongMap, ReadsOpenExrFilesAndNamesBadOnes) {
  const auto dir = temp_dir();
  const std::string path = (dir / "sky.EXR").string();  // the extension in any case
  // Values exact in half precision.
  write_exr(path, 8, 4, [](int i, int j) { return RgbD{0.25 * (i + 1), 0.5, 2.0 * j}; });
  std::string problem;
  const auto map = load_latlong_map(path, problem);
  ASSERT_TRUE(map) << problem;
  EXPECT_EQ(map->width(), 8);
  EXPECT_EQ(map->texel(3, 0).r, 1.0f);
  EXPECT_EQ(map->texel(3, 2).b, 4.0f);
  EXPECT_EQ(map->texel(0, 1).g, 0.5f);
  // Truncated by half: OpenEXR's own error, one line.
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string cut = (dir / "cut.exr").string();
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  EXPECT_FALSE(load_latlong_map(cut, problem));
  EXPECT_NE(problem.find("OpenEXR"), std::string::npos) << problem;
  EXPECT_EQ(problem.find('\n'), std::string::npos) << problem;
  const std::string square = (dir / "square.exr").string();
  write_exr(square, 4, 4, [](int, int) { return RgbD{1, 1, 1}; });
  EXPECT_FALSE(load_latlong_map(square, problem));
  EXPECT_NE(problem.find("twice as wide as high"), std::string::npos) << problem;
  const std::string negative = (dir / "negative.exr").string();
  write_exr(negative, 4, 2, [](int i, int) { return RgbD{i == 3 ? -1.0 : 1.0, 1, 1}; });
  EXPECT_FALSE(load_latlong_map(negative, problem));
  EXPECT_NE(problem.find("negative or non-finite texel (column 3, row 0)"), std::string::npos)
      << problem;
  EXPECT_FALSE(load_latlong_map((dir / "none.exr").string(), problem));
  EXPECT_EQ(problem, "no such file");
  std::filesystem::remove_all(dir);
}

/// Writes a w x h OpenEXR image of 32-bit float channels `names` (each texel's channel c is
/// f(i, j)[c]).
template <class F>
void write_float_exr(const std::string& path, int w, int h, const std::vector<std::string>& names,
                     F f) {
  const std::size_t n = static_cast<std::size_t>(w) * h, nc = names.size();
  std::vector<float> px(n * nc);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      for (std::size_t c = 0; c < nc; ++c)
        px[(static_cast<std::size_t>(j) * w + i) * nc + c] = f(i, j)[c];
  Imf::Header header(w, h);
  Imf::FrameBuffer frame;
  for (std::size_t c = 0; c < nc; ++c) {
    header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
    frame.insert(names[c],
                 Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(px.data() + c), nc * sizeof(float),
                            nc * sizeof(float) * static_cast<std::size_t>(w)));
  }
  Imf::OutputFile out(path.c_str(), header);
  out.setFrameBuffer(frame);
  out.writePixels(h);
}

// Issue 27: a 32-bit float environment with a texel above half precision's largest value (65504)
// was refused as "negative or non-finite" (read through half floats). Float channels are now read
// as floats, exactly; a lone luminance channel Y as grey; infinity is still refused.
TEST(LatLongMap, FloatExrKeepsTexelsAboveTheHalfRange) {
  const auto dir = temp_dir();
  const std::string sun = (dir / "sun.exr").string();
  write_float_exr(sun, 8, 4, {"R", "G", "B"}, [](int i, int j) {
    return std::array<float, 3>{i == 5 && j == 1 ? 70000.0f : 0.3f, 1e30f, 1.0f / 3.0f};
  });
  std::string problem;
  const auto map = load_latlong_map(sun, problem);
  ASSERT_TRUE(map) << problem;
  EXPECT_EQ(map->texel(5, 1).r, 70000.0f);
  EXPECT_EQ(map->texel(4, 1).r, 0.3f);  // not rounded to half (0.2998...)
  EXPECT_EQ(map->texel(0, 3).g, 1e30f);
  EXPECT_EQ(map->texel(7, 0).b, 1.0f / 3.0f);
  const std::string grey = (dir / "grey.exr").string();
  write_float_exr(grey, 4, 2, {"Y"},
                  [](int i, int) { return std::array<float, 1>{100000.0f + i}; });
  const auto y = load_latlong_map(grey, problem);
  ASSERT_TRUE(y) << problem;
  EXPECT_EQ(y->texel(2, 1).r, 100002.0f);
  EXPECT_EQ(y->texel(2, 1).b, 100002.0f);
  const std::string inf = (dir / "inf.exr").string();
  write_float_exr(inf, 4, 2, {"R", "G", "B"}, [](int i, int) {
    return std::array<float, 3>{1, i == 1 ? std::numeric_limits<float>::infinity() : 1.0f, 1};
  });
  EXPECT_FALSE(load_latlong_map(inf, problem));
  EXPECT_NE(problem.find("non-finite texel (column 1, row 0)"), std::string::npos) << problem;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace thaw::render
