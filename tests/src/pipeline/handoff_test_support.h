#pragma once
// What the hand-off tests with real peers share (test_handoff_blender_e2e.cpp,
// test_handoff_paraview_e2e.cpp): a small default film written with EXR frames, the EXR's layers
// and camera attributes read back, PNGs read back, the silhouette of the ice compared pixel by
// pixel, and pictures for docs/handoff.md. Written once here.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfMatrixAttribute.h>
#include <OpenEXR/ImfStringVectorAttribute.h>
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "base/subprocess.h"
#include "render/image/image.h"
#include "render/image/image_io.h"
#include "tests/src/pipeline/run_test_support.h"

namespace thaw::pipeline::test {

inline const fs::path kHandoffShots = fs::path(THAW_BINARY_DIR) / "handoff_screenshots";

struct Rgba8 {
  int width = 0, height = 0;
  std::vector<unsigned char> pixels;  // RGBA, row 0 at the top
};

inline Rgba8 read_png(const fs::path& path) {
  Rgba8 img;
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &img.width, &img.height, &channels, 4);
  EXPECT_NE(data, nullptr) << path;
  if (!data) return img;
  img.pixels.assign(data, data + std::size_t(4) * img.width * img.height);
  stbi_image_free(data);
  return img;
}

/// The EXR layers thaw wrote for a frame, and its camera attributes.
struct ExrFrame {
  int width = 0, height = 0;
  std::vector<float> r, g, b, depth, nx, ny, nz, object_id;
  std::vector<std::string> object_names;
  Imath::M44f world_to_ndc, world_to_camera;

  /// 1-based id of the named object in id.object (0: the object is not in the frame).
  float id_of(const std::string& name) const {
    const auto it = std::find(object_names.begin(), object_names.end(), name);
    return it == object_names.end() ? 0.0f : static_cast<float>(it - object_names.begin() + 1);
  }
};

inline ExrFrame read_exr(const fs::path& path) {
  Imf::InputFile in(path.c_str());
  const Imath::Box2i dw = in.header().dataWindow();
  ExrFrame f;
  f.width = dw.max.x - dw.min.x + 1, f.height = dw.max.y - dw.min.y + 1;
  const std::size_t n = std::size_t(f.width) * f.height;
  Imf::FrameBuffer fb;
  const auto slice = [&](const char* name, std::vector<float>& v) {
    v.assign(n, 0.0f);
    fb.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(v.data()), sizeof(float),
                               sizeof(float) * f.width));
  };
  slice("R", f.r), slice("G", f.g), slice("B", f.b), slice("Z", f.depth);
  slice("N.X", f.nx), slice("N.Y", f.ny), slice("N.Z", f.nz), slice("id.object", f.object_id);
  in.setFrameBuffer(fb);
  in.readPixels(dw.min.y, dw.max.y);
  f.object_names = in.header().typedAttribute<Imf::StringVectorAttribute>("thaw.objectIds").value();
  f.world_to_ndc = in.header().typedAttribute<Imf::M44fAttribute>("worldToNDC").value();
  f.world_to_camera = in.header().typedAttribute<Imf::M44fAttribute>("worldToCamera").value();
  return f;
}

/// A picture for the docs from display values in [0, 1] (write_png encodes linear as sRGB).
inline void write_display_png(const fs::path& path, int w, int h,
                              const std::function<std::array<float, 3>(int, int)>& colour) {
  render::Image img(w, h);
  const auto linear = [](float v) {
    v = std::clamp(v, 0.0f, 1.0f);
    return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto c = colour(x, y);
      img.at(x, y) = render::Rgb(linear(c[0]), linear(c[1]), linear(c[2]));
    }
  render::write_png(path, img);
}

/// The default scenario filmed small: `frames` output steps, EXR frames beside the PNGs, at
/// width x height and 1 sample per pixel, into DIR/out. Returns thaw run's exit code and output.
inline ProcessResult film_small_default(const fs::path& dir, int frames, int width, int height) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string text = run_process({kThaw.string(), "run", "--print-default"}).output;
  const auto edit = [&](const std::string& from, const std::string& to) {
    const auto p = text.find(from);
    EXPECT_NE(p, std::string::npos) << from;
    if (p != std::string::npos) text.replace(p, from.size(), to);
  };
  edit("frames = 80 ", "frames = " + std::to_string(frames) + " ");
  edit("gif = false", "gif = false\nframes_format = \"exr\"");
  std::ofstream(dir / "default_small.toml") << text;
  return run_process({kThaw.string(), "run", (dir / "default_small.toml").string(), "--out",
                      (dir / "out").string(), "--size",
                      std::to_string(width) + "x" + std::to_string(height), "--spp", "1", "-q"});
}

/// Pixel-by-pixel agreement of thaw's silhouette of one object (the EXR's object ids at the
/// pixel centres) with a peer's mask (white where the peer drew the object).
struct SilhouetteAgreement {
  long pixels = 0, agree = 0, thaw_only = 0, peer_only = 0, both = 0;
  std::vector<int> kind;  // per pixel: 1 thaw only, 2 peer only, 3 both, 0 neither

  double fraction() const { return pixels ? double(agree) / double(pixels) : 0.0; }
  long thaw() const { return thaw_only + both; }
  long peer() const { return peer_only + both; }

  /// The picture of docs/handoff.md: white both, red thaw only, blue the peer only, grey neither.
  void write_png(const fs::path& path, int width, int height) const {
    write_display_png(path, width, height, [&](int x, int y) {
      switch (kind[std::size_t(y) * width + x]) {
        case 3:
          return std::array<float, 3>{1, 1, 1};
        case 1:
          return std::array<float, 3>{1, 0, 0};
        case 2:
          return std::array<float, 3>{0, 0.3f, 1};
        default:
          return std::array<float, 3>{0.15f, 0.15f, 0.15f};
      }
    });
  }
};

/// `peer_has(i)`: whether the peer's mask covers pixel i (row-major, row 0 at the top).
inline SilhouetteAgreement compare_silhouettes(const ExrFrame& thaw, float object_id,
                                               const std::function<bool(std::size_t)>& peer_has) {
  SilhouetteAgreement s;
  s.pixels = long(thaw.width) * thaw.height;
  s.kind.resize(std::size_t(s.pixels));
  for (std::size_t i = 0; i < s.kind.size(); ++i) {
    const bool t = thaw.object_id[i] == object_id, p = peer_has(i);
    s.agree += t == p, s.thaw_only += t && !p, s.peer_only += p && !t, s.both += t && p;
    s.kind[i] = t + 2 * p;
  }
  return s;
}

}  // namespace thaw::pipeline::test
