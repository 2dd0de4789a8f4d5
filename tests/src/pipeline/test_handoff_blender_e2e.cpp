// The Blender hand-off with the real program (issue 29): `thaw run` films a small default run
// (160 x 120, EXR frames), then Debian's blender runs DIR/handoff/blender_scene.py, renders frame
// kFrame with Cycles, renders the ice's silhouette and projects thaw's corner points through its
// camera. The silhouette must agree with thaw's (the EXR's object ids at the pixel centres) on at
// least 98 % of the pixels, and the camera must put the corners within 0.1 pixel. The pictures go
// to BUILD/handoff_screenshots/ (docs/handoff.md shows them). Labelled `blender`.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfMatrixAttribute.h>
#include <OpenEXR/ImfStringVectorAttribute.h>
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "base/subprocess.h"
#include "render/image/image.h"
#include "render/image/image_io.h"
#include "tests/src/pipeline/run_test_support.h"

namespace thaw::pipeline {
namespace {

using namespace test;
namespace fs = std::filesystem;

const fs::path kBlender = THAW_BLENDER;
const fs::path kShots = fs::path(THAW_BINARY_DIR) / "handoff_screenshots";
constexpr int kFrame = 3;
constexpr int kWidth = 160, kHeight = 120;

struct Rgba8 {
  int width = 0, height = 0;
  std::vector<unsigned char> pixels;  // RGBA, row 0 at the top
};

Rgba8 read_png(const fs::path& path) {
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
};

ExrFrame read_exr(const fs::path& path) {
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
void write_display_png(const fs::path& path, int w, int h,
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

class BlenderHandoff : public ::testing::Test {
 protected:
  static fs::path s_dir, s_out;
  static std::string s_run_output;
  static int s_run_exit;

  /// One run for the suite: the default scenario with 8 frames (6 before break-through) as EXR.
  static void SetUpTestSuite() {
    s_dir = fs::temp_directory_path() / ("thaw_test_blender_" + std::to_string(::getpid()));
    fs::remove_all(s_dir);
    fs::create_directories(s_dir);
    s_out = s_dir / "out";
    const ProcessResult def = run_process({kThaw.string(), "run", "--print-default"});
    std::string text = def.output;
    const auto edit = [&](const std::string& from, const std::string& to) {
      const auto p = text.find(from);
      ASSERT_NE(p, std::string::npos) << from;
      text.replace(p, from.size(), to);
    };
    edit("frames = 80 ", "frames = 8 ");
    edit("gif = false", "gif = false\nframes_format = \"exr\"");
    std::ofstream(s_dir / "default_small.toml") << text;
    const ProcessResult r = run_process(
        {kThaw.string(), "run", (s_dir / "default_small.toml").string(), "--out", s_out.string(),
         "--size", std::to_string(kWidth) + "x" + std::to_string(kHeight), "--spp", "1", "-q"});
    s_run_exit = r.exit_code;
    s_run_output = r.output;
  }
  static void TearDownTestSuite() { fs::remove_all(s_dir); }

  ProcessResult blender(std::vector<std::string> args) {
    args.insert(args.begin(), {kBlender.string(), "--background", "--factory-startup", "--python",
                               (s_out / "handoff" / "blender_scene.py").string(), "--"});
    return run_process(args);
  }
};
fs::path BlenderHandoff::s_dir, BlenderHandoff::s_out;
std::string BlenderHandoff::s_run_output;
int BlenderHandoff::s_run_exit = -1;

TEST_F(BlenderHandoff, CyclesRendersTheFrameWithThawsSilhouetteAndCamera) {
  ASSERT_EQ(s_run_exit, 0) << s_run_output;
  const fs::path dir = s_dir / "blender";
  fs::create_directories(dir);
  const ProcessResult r =
      blender({"--frame", std::to_string(kFrame), "--render", (dir / "cycles.png").string(),
               "--samples", "16", "--mask", (dir / "mask.png").string(), "--camera-check",
               (dir / "camera.json").string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;

  // The silhouette: thaw's first surface at each pixel centre (the EXR's object ids) against
  // Blender's (the mask render's alpha, also one ray through each pixel centre).
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06d", kFrame);
  const ExrFrame thaw = read_exr(s_out / "frames" / (std::string(name) + ".exr"));
  const auto ice = std::find(thaw.object_names.begin(), thaw.object_names.end(),
                             std::string("shell outer surface"));
  ASSERT_NE(ice, thaw.object_names.end());
  const float ice_id = static_cast<float>(ice - thaw.object_names.begin() + 1);
  const Rgba8 mask = read_png(dir / "mask.png");
  ASSERT_EQ(mask.width, kWidth);
  ASSERT_EQ(mask.height, kHeight);
  ASSERT_EQ(thaw.width, kWidth);
  long agree = 0, thaw_ice = 0, blender_ice = 0, both = 0;
  std::vector<int> kind(std::size_t(kWidth) * kHeight);
  for (std::size_t i = 0; i < kind.size(); ++i) {
    const bool t = thaw.object_id[i] == ice_id, b = mask.pixels[4 * i + 3] > 127;
    agree += t == b, thaw_ice += t, blender_ice += b, both += t && b;
    kind[i] = t + 2 * b;
  }
  const double n = static_cast<double>(kind.size());
  // The ice must be a real part of the picture, or agreeing would mean nothing.
  EXPECT_GT(thaw_ice, n / 50) << "thaw's frame shows little ice";
  EXPECT_GT(blender_ice, n / 50) << "Blender's mask shows little ice";
  EXPECT_GE(agree / n, 0.98) << "thaw ice " << thaw_ice << ", Blender ice " << blender_ice
                             << ", both " << both;
  std::printf("silhouette: %.4f of %ld pixels agree; ice: thaw %ld, Blender %ld, both %ld\n",
              agree / n, long(n), thaw_ice, blender_ice, both);

  // The camera: Blender's projection of the world points thaw's rays through the image corners
  // reach (handoff/camera.json), and the EXR header's worldToNDC of the same points.
  const auto check = nlohmann::json::parse(read_file(dir / "camera.json"));
  EXPECT_LT(check["max_error_px"].get<double>(), 0.1) << check.dump(1);
  std::printf("camera: Blender's corners within %.2e px of thaw's\n",
              check["max_error_px"].get<double>());
  const auto cam = nlohmann::json::parse(read_file(s_out / "handoff" / "camera.json"));
  for (const auto& c : cam["corner_points"]) {
    const Imath::V3f p(c["world_m"][0].get<float>(), c["world_m"][1].get<float>(),
                       c["world_m"][2].get<float>());
    Imath::V3f ndc;
    thaw.world_to_ndc.multVecMatrix(p, ndc);  // row vector, divided by w
    const double px = 0.5 * (ndc.x + 1) * kWidth, py = 0.5 * (1 - ndc.y) * kHeight;
    EXPECT_NEAR(px, c["pixel"][0].get<double>(), 0.1);
    EXPECT_NEAR(py, c["pixel"][1].get<double>(), 0.1);
    Imath::V3f in_camera;  // in front of the camera: negative z
    thaw.world_to_camera.multVecMatrix(p, in_camera);
    EXPECT_LT(in_camera.z, 0.0f);
  }

  // ParaView's camera configuration holds the same view angle.
  char fov[64];
  std::snprintf(fov, sizeof fov, "value=\"%.17g\"", cam["vertical_fov_deg"].get<double>());
  const std::string pvcc = read_file(s_out / "handoff" / "paraview_camera.pvcc");
  EXPECT_NE(pvcc.find("<Property name=\"CameraViewAngle\""), std::string::npos) << pvcc;
  EXPECT_NE(pvcc.find(fov), std::string::npos) << pvcc;

  // The pictures of docs/handoff.md.
  fs::create_directories(kShots);
  fs::copy_file(dir / "cycles.png", kShots / "blender_cycles.png",
                fs::copy_options::overwrite_existing);
  fs::copy_file(s_out / "frames" / (std::string(name) + ".png"), kShots / "thaw_frame.png",
                fs::copy_options::overwrite_existing);
  // Silhouettes: white both, red thaw only, blue Blender only, dark grey neither.
  write_display_png(kShots / "silhouettes.png", kWidth, kHeight, [&](int x, int y) {
    switch (kind[std::size_t(y) * kWidth + x]) {
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
  // The EXR's layers side by side: beauty (linear, clipped), N (0.5 + 0.5 n), id.object (one
  // grey per object), Z (near bright, far dark).
  float zmax = 0;
  for (float z : thaw.depth)
    if (std::isfinite(z)) zmax = std::max(zmax, std::min(z, 3.0f));
  write_display_png(kShots / "exr_layers.png", 4 * kWidth, kHeight, [&](int x, int y) {
    const std::size_t i = std::size_t(y) * kWidth + x % kWidth;
    const auto srgb = [](float v) {
      v = std::clamp(v, 0.0f, 1.0f);
      return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
    };
    switch (x / kWidth) {
      case 0:
        return std::array<float, 3>{srgb(thaw.r[i]), srgb(thaw.g[i]), srgb(thaw.b[i])};
      case 1:
        return std::array<float, 3>{0.5f + 0.5f * thaw.nx[i], 0.5f + 0.5f * thaw.ny[i],
                                    0.5f + 0.5f * thaw.nz[i]};
      case 2: {
        const float v = thaw.object_id[i] / static_cast<float>(thaw.object_names.size());
        return std::array<float, 3>{v, v, v};
      }
      default: {
        const float v =
            std::isfinite(thaw.depth[i]) ? 1 - std::min(thaw.depth[i], zmax) / zmax : 0.0f;
        return std::array<float, 3>{v, v, v};
      }
    }
  });
}

TEST_F(BlenderHandoff, BadInputIsOneLineNamingWhatIsWrong) {
  ASSERT_EQ(s_run_exit, 0) << s_run_output;
  // Not inside Blender: the version it needs.
  const ProcessResult py =
      run_process({"python3", (s_out / "handoff" / "blender_scene.py").string()});
  EXPECT_EQ(py.exit_code, 2);
  EXPECT_NE(py.output.find("thaw hand-off: this script needs Blender 3.0 or newer"),
            std::string::npos)
      << py.output;
  const ProcessResult frame = blender({"--frame", "99"});
  EXPECT_EQ(frame.exit_code, 2) << frame.output;
  EXPECT_NE(frame.output.find("thaw hand-off: --frame 99 is not a frame of this run (0 to 5)"),
            std::string::npos)
      << frame.output;
  // An incomplete run folder: the missing file and its stage.
  const fs::path copy = s_dir / "incomplete";
  fs::copy(s_out, copy, fs::copy_options::recursive);
  fs::remove(copy / "sim" / "mesh" / "step_000002_outer.obj");
  const ProcessResult missing =
      run_process({kBlender.string(), "--background", "--factory-startup", "--python",
                   (copy / "handoff" / "blender_scene.py").string()});
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("sim/mesh/step_000002_outer.obj is missing (the mesh stage"),
            std::string::npos)
      << missing.output;
}

}  // namespace
}  // namespace thaw::pipeline
