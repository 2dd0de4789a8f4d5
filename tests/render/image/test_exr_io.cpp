// Tests render/image/exr_io.h by reading the files back with OpenEXR's own reader: the channel
// list and types, the half RGBA against the float image (and its PFM) within half precision,
// the float layers exactly, the metadata, and the file written through write_image/check paths.
#include "render/image/exr_io.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfStringVectorAttribute.h>
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "render/image/image_io.h"

namespace thaw::render {
namespace {

/// Every channel of an EXR file as floats (OpenEXR converts half to float exactly), with the
/// stored pixel types and the header.
struct ReadBack {
  int width = 0, height = 0;
  std::map<std::string, Imf::PixelType> types;
  std::map<std::string, std::vector<float>> channels;
  std::unique_ptr<Imf::Header> header;
};

ReadBack read_exr(const std::string& bytes) {
  Imf::StdISStream stream;
  stream.str(bytes);
  Imf::InputFile in(stream);
  ReadBack r;
  r.header = std::make_unique<Imf::Header>(in.header());
  const Imath::Box2i dw = in.header().dataWindow();
  r.width = dw.max.x - dw.min.x + 1;
  r.height = dw.max.y - dw.min.y + 1;
  Imf::FrameBuffer fb;
  for (auto it = in.header().channels().begin(); it != in.header().channels().end(); ++it) {
    r.types[it.name()] = it.channel().type;
    auto& v = r.channels[it.name()];
    v.resize(std::size_t(r.width) * r.height);
    fb.insert(it.name(), Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(v.data()), sizeof(float),
                                    sizeof(float) * std::size_t(r.width)));
  }
  in.setFrameBuffer(fb);
  in.readPixels(dw.min.y, dw.max.y);
  return r;
}

/// Half precision: 10 stored mantissa bits, round to nearest, so a normal value (|v| >= 2^-14)
/// is within |v| 2^-11 and a subnormal one within half its spacing 2^-24 / 2 = 2^-25.
double half_tolerance(double v) {
  return std::max(std::abs(v) * std::ldexp(1.0, -11), std::ldexp(1.0, -25));
}

/// The float pixels (r, g, b) of a PFM written by encode_pfm (bottom row first).
std::vector<float> pfm_floats(const std::string& pfm, int w, int h, int x, int y) {
  const std::size_t header = pfm.find("-1.0\n") + 5;
  std::vector<float> v(3);
  std::memcpy(v.data(), pfm.data() + header + (std::size_t(h - 1 - y) * w + x) * 12, 12);
  return v;
}

Image test_image(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      // from 1e-6 (half subnormal) through O(1) to 3e4 (near half's largest, 65504)
      const float v = 1e-6f * std::pow(3e10f, float(y * w + x) / float(w * h - 1));
      img.at(x, y) = Rgb{v, 0.37f * v, 0.5f + 0.01f * float(x)};
    }
  return img;
}

TEST(ExrIo, BeautyHalfRgbaMatchesFloatAndPfmWithinHalfPrecision) {
  const int w = 23, h = 17;
  const Image img = test_image(w, h);
  const ReadBack r = read_exr(encode_exr(
      img, nullptr, ExrMetadata{"scene.toml", std::nullopt, 4, 0.5, std::nullopt, std::nullopt}));
  ASSERT_EQ(r.width, w);
  ASSERT_EQ(r.height, h);
  ASSERT_EQ(r.types.size(), 4u);
  for (const char* c : {"R", "G", "B", "A"}) EXPECT_EQ(r.types.at(c), Imf::HALF) << c;
  const std::string pfm = encode_pfm(img);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      const std::vector<float> f = pfm_floats(pfm, w, h, x, y);
      EXPECT_NEAR(r.channels.at("R")[i], f[0], half_tolerance(f[0])) << x << "," << y;
      EXPECT_NEAR(r.channels.at("G")[i], f[1], half_tolerance(f[1]));
      EXPECT_NEAR(r.channels.at("B")[i], f[2], half_tolerance(f[2]));
      EXPECT_EQ(r.channels.at("A")[i], 1.0f);  // no AOVs: opaque
      EXPECT_EQ(f[0], img.at(x, y).r);         // the PFM is the float image itself
    }
  // The tolerance is tight: the same image through half must sometimes be off by more than a
  // quarter of it (else half rounding would not be tested at all).
  double worst = 0;
  for (int i = 0; i < w * h; ++i) {
    const double v = img.pixels()[i].g;
    worst = std::max(worst, std::abs(r.channels.at("G")[i] - v) / half_tolerance(v));
  }
  EXPECT_GT(worst, 0.25);
  EXPECT_LE(worst, 1.0);
}

TEST(ExrIo, AovLayersAndMetadata) {
  const int w = 8, h = 5;
  const Image img = test_image(w, h);
  AovImage aov(w, h);
  aov.object_names = {"floor", "shell"};
  aov.medium_names = {"vacuum", "ice", "water"};
  for (int i = 0; i < w * h; ++i) {
    aov.depth[i] = i == 3 ? std::numeric_limits<float>::infinity() : 1.0f + 0.123456789f * i;
    const float a = 0.3f * i;
    aov.normal[i] = Vec3{std::cos(a), std::sin(a), 0.0f};
    aov.object_id[i] = static_cast<std::uint32_t>(i % 3);
    aov.medium_id[i] = static_cast<std::uint32_t>(i % 4);
    aov.alpha[i] = 0.25f * (i % 5);
  }
  const ReadBack r = read_exr(encode_exr(
      img, &aov, ExrMetadata{"data/scenes/x.toml", 754.5, 16, -1.0, std::nullopt, std::nullopt}));
  const std::map<std::string, Imf::PixelType> expected = {
      {"R", Imf::HALF},          {"G", Imf::HALF},         {"B", Imf::HALF},   {"A", Imf::HALF},
      {"Z", Imf::FLOAT},         {"N.X", Imf::HALF},       {"N.Y", Imf::HALF}, {"N.Z", Imf::HALF},
      {"id.object", Imf::FLOAT}, {"id.medium", Imf::FLOAT}};
  EXPECT_EQ(r.types, expected);
  for (int i = 0; i < w * h; ++i) {
    EXPECT_EQ(r.channels.at("Z")[i], aov.depth[i]);  // float: exact, infinity included
    EXPECT_NEAR(r.channels.at("N.X")[i], aov.normal[i].x, half_tolerance(aov.normal[i].x));
    EXPECT_NEAR(r.channels.at("N.Y")[i], aov.normal[i].y, half_tolerance(aov.normal[i].y));
    EXPECT_EQ(r.channels.at("N.Z")[i], 0.0f);
    EXPECT_EQ(r.channels.at("id.object")[i], float(aov.object_id[i]));
    EXPECT_EQ(r.channels.at("id.medium")[i], float(aov.medium_id[i]));
    EXPECT_EQ(r.channels.at("A")[i], aov.alpha[i]);  // quarters are exact in half
  }
  const Imf::Header& hd = *r.header;
  EXPECT_EQ(hd.compression(), Imf::ZIP_COMPRESSION);
  EXPECT_EQ(hd.typedAttribute<Imf::StringAttribute>("thaw.sceneFile").value(),
            "data/scenes/x.toml");
  EXPECT_EQ(hd.typedAttribute<Imf::DoubleAttribute>("thaw.simulatedTime_s").value(), 754.5);
  EXPECT_EQ(hd.typedAttribute<Imf::IntAttribute>("thaw.samplesPerPixel").value(), 16);
  EXPECT_EQ(hd.typedAttribute<Imf::DoubleAttribute>("thaw.exposure_stops").value(), -1.0);
  EXPECT_EQ(hd.typedAttribute<Imf::StringVectorAttribute>("thaw.objectIds").value(),
            aov.object_names);
  EXPECT_EQ(hd.typedAttribute<Imf::StringVectorAttribute>("thaw.mediumIds").value(),
            aov.medium_names);
  EXPECT_EQ(hd.typedAttribute<Imf::StringAttribute>("software").value().rfind("thaw ", 0), 0u);
}

TEST(ExrIo, NoTimeAttributeWhenTheTimeIsUnknown) {
  const ReadBack r = read_exr(encode_exr(Image(2, 2), nullptr, ExrMetadata{}));
  EXPECT_EQ(r.header->findTypedAttribute<Imf::DoubleAttribute>("thaw.simulatedTime_s"), nullptr);
}

TEST(ExrIo, WriteImageAcceptsExr) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("thaw_exr_io_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  EXPECT_TRUE(is_exr_path(dir / "a.EXR"));
  EXPECT_FALSE(is_exr_path(dir / "a.png"));
  EXPECT_NO_THROW(check_output_path(dir / "a.exr"));
  write_image(dir / "a.exr", test_image(4, 3));
  Imf::InputFile in((dir / "a.exr").c_str());
  EXPECT_EQ(in.header().dataWindow().max.x, 3);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace thaw::render
