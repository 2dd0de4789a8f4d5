// The Blender hand-off with the real program (issue 29): `thaw run` films a small default run
// (160 x 120, EXR frames), then Debian's blender runs DIR/handoff/blender_scene.py, renders frame
// kFrame with Cycles, renders the ice's silhouette and projects thaw's corner points through its
// camera. The silhouette must agree with thaw's (the EXR's object ids at the pixel centres) on at
// least 98 % of the pixels, and the camera must put the corners within 0.1 pixel. The pictures go
// to BUILD/handoff_screenshots/ (docs/handoff.md shows them). Labelled `blender`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/src/pipeline/handoff_test_support.h"

namespace thaw::pipeline {
namespace {

using namespace test;
namespace fs = std::filesystem;

const fs::path kBlender = THAW_BLENDER;
constexpr int kFrame = 3;
constexpr int kWidth = 160, kHeight = 120;

class BlenderHandoff : public ::testing::Test {
 protected:
  static fs::path s_dir, s_out;
  static std::string s_run_output;
  static int s_run_exit;

  /// One run for the suite: the default scenario with 8 frames (6 before break-through) as EXR.
  static void SetUpTestSuite() {
    s_dir = fs::temp_directory_path() / ("thaw_test_blender_" + std::to_string(::getpid()));
    s_out = s_dir / "out";
    const ProcessResult r = film_small_default(s_dir, 8, kWidth, kHeight);
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
  const float ice_id = thaw.id_of("shell outer surface");
  ASSERT_GT(ice_id, 0.0f);
  const Rgba8 mask = read_png(dir / "mask.png");
  ASSERT_EQ(mask.width, kWidth);
  ASSERT_EQ(mask.height, kHeight);
  ASSERT_EQ(thaw.width, kWidth);
  const SilhouetteAgreement s = compare_silhouettes(
      thaw, ice_id, [&](std::size_t i) { return mask.pixels[4 * i + 3] > 127; });
  // The ice must be a real part of the picture, or agreeing would mean nothing.
  EXPECT_GT(s.thaw(), s.pixels / 50) << "thaw's frame shows little ice";
  EXPECT_GT(s.peer(), s.pixels / 50) << "Blender's mask shows little ice";
  EXPECT_GE(s.fraction(), 0.98) << "thaw ice " << s.thaw() << ", Blender ice " << s.peer()
                                << ", both " << s.both;
  std::printf("silhouette: %.4f of %ld pixels agree; ice: thaw %ld, Blender %ld, both %ld\n",
              s.fraction(), s.pixels, s.thaw(), s.peer(), s.both);

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
  fs::create_directories(kHandoffShots);
  fs::copy_file(dir / "cycles.png", kHandoffShots / "blender_cycles.png",
                fs::copy_options::overwrite_existing);
  fs::copy_file(s_out / "frames" / (std::string(name) + ".png"), kHandoffShots / "thaw_frame.png",
                fs::copy_options::overwrite_existing);
  s.write_png(kHandoffShots / "silhouettes.png", kWidth, kHeight);
  // The EXR's layers side by side: beauty (linear, clipped), N (0.5 + 0.5 n), id.object (one
  // grey per object), Z (near bright, far dark).
  float zmax = 0;
  for (float z : thaw.depth)
    if (std::isfinite(z)) zmax = std::max(zmax, std::min(z, 3.0f));
  write_display_png(kHandoffShots / "exr_layers.png", 4 * kWidth, kHeight, [&](int x, int y) {
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
