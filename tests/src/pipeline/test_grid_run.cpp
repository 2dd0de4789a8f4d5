// End-to-end test of `thaw run` on a grid (3D) scenario (tests/src/pipeline/data/tiny_cube.toml):
// the real thaw binary simulates a small hollow ice cube on the grid, meshes every frame's fields
// (src/mesh/grid_series.h) and renders the film. Checks the mesh contract the renderer relies on
// (closed outward surfaces: the render stage refuses others), the cavity's surface until the
// break-through and none after, and byte-identical frames on a rerun with --force.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cstdio>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/subprocess.h"
#include "src/pipeline/film_encoder.h"

namespace thaw::pipeline {
namespace {
namespace fs = std::filesystem;

const fs::path kThaw = fs::path(THAW_BINARY_DIR) / "thaw";
const fs::path kCube = fs::path(THAW_SOURCE_DIR) / "tests/src/pipeline/data/tiny_cube.toml";

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ThawRunGrid, HollowCubeMeltsBreaksThroughAndIsFilmed) {
  const fs::path dir =
      fs::temp_directory_path() / ("thaw_test_grid_run_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const fs::path out = dir / "out";
  const auto run =
      run_process({kThaw.string(), "run", kCube.string(), "--out", out.string(), "--jobs", "2"});
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto manifest = nlohmann::json::parse(read_file(out / "sim/mesh/manifest.json"));
  // Every file and folder of the run folder is in docs/user-guide.md's table (issue 27).
  const std::string guide = read_file(fs::path(THAW_SOURCE_DIR) / "docs/user-guide.md");
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_NE(guide.find("`DIR/" + e.path().filename().string()), std::string::npos)
        << "docs/user-guide.md's table does not list " << e.path().filename();
  EXPECT_EQ(manifest["geometry"]["geometry"], "grid");
  const auto& steps = manifest["steps"];
  ASSERT_GE(steps.size(), 3u);
  // t = 0: the sealed, water-filled cavity inside the cube.
  EXPECT_EQ(steps[0]["cavities"], 1);
  EXPECT_TRUE(steps[0]["inner"].is_string());
  EXPECT_GT(steps[0]["cavity_water_fraction"].get<double>(), 0.9);
  // The meshes hold the field's volumes (docs/mesh.md bound: 0.0858 h A + h^2 L; here A < 30 cm^2
  // and L < 50 cm for the cube and its cavity, h = 1 mm: 2.6e-7 + 5e-7 m^3).
  for (const char* part : {"outer", "inner"})
    EXPECT_NEAR(steps[0][std::string(part) + "_volume_m3"].get<double>(),
                steps[0][std::string(part) + "_exact_volume_m3"].get<double>(), 7.6e-7)
        << part;
  // After the break-through (250 s in tiny_cube.toml) a frame with ice left has one surface and no
  // cavity; by the end nothing is sealed.
  bool open_with_ice = false;
  for (const auto& s : steps)
    if (s["outer"].is_string() && s["cavities"] == 0) {
      EXPECT_TRUE(s["inner"].is_null()) << s["step"];
      open_with_ice = true;
    }
  EXPECT_TRUE(open_with_ice);
  EXPECT_TRUE(steps[steps.size() - 1]["inner"].is_null());
  const auto summary = nlohmann::json::parse(read_file(out / "sim/summary.json"));
  EXPECT_NE(summary.dump().find("break_through"), std::string::npos);
  // The film opens the shell exactly when the solver does: sealed before its break_through,
  // open from then on (docs/mesh.md, "Topology as the solver sees it").
  for (const auto& e : summary["events"]) {
    if (e["kind"] != "break_through") continue;
    for (const auto& s : steps) {
      if (!s["outer"].is_string()) continue;
      EXPECT_EQ(s["cavities"], s["time_s"].get<double>() < e["time_s"].get<double>() ? 1 : 0)
          << "step " << s["step"] << " at " << s["time_s"] << " s";
    }
  }
  EXPECT_EQ(count_video_frames(out / "melt.mp4"), static_cast<int>(steps.size()));
  // The solver's fields as a ParaView image series, one .vti per step (issue 13).
  EXPECT_TRUE(std::filesystem::exists(out / "fields.pvd"));
  for (std::size_t k = 0; k < steps.size(); ++k) {
    char name[64];
    std::snprintf(name, sizeof name, "fields_vti/step_%06zu.vti", k);
    EXPECT_TRUE(std::filesystem::exists(out / name)) << name;
  }
  const std::string frame0 = read_file(out / "frames/frame_000000.png");
  const auto again = run_process(
      {kThaw.string(), "run", kCube.string(), "--out", out.string(), "--force", "--jobs", "1"});
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(read_file(out / "frames/frame_000000.png"), frame0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace thaw::pipeline
