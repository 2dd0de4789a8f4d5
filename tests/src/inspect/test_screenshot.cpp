// End-to-end tests of src/inspect/screenshot (needs X: a display or Xvfb; skipped without).
#include "src/inspect/screenshot.h"

#include <gtest/gtest.h>

#include "base/error.h"
#include "tests/src/inspect/render_check.h"
#include "tests/src/inspect/test_meshes.h"

namespace thaw::inspect {
namespace {
namespace fs = std::filesystem;

TEST(Screenshot, ObjPanelShowsTheMesh) {
  THAW_SKIP_WITHOUT_X();
  testing::ScratchDir dir("shot");
  meshio::write_obj(dir.path() / "ball.obj", testing::icosphere(0.02, 2));
  const fs::path png = dir.path() / "ball.png";
  write_obj_screenshot(dir.path() / "ball.obj", png);
  const auto image = testing::read_png(png);
  int dims[3];
  image->GetDimensions(dims);
  const int panel = ScreenshotOptions{}.panel_size_px;
  EXPECT_EQ(dims[0], panel);
  EXPECT_GT(dims[1], panel);  // plus the title band
  // The sphere fills the panel's centre; the corner is background: they must differ.
  const auto centre = testing::pixel(image, panel / 2, panel / 2);
  const auto corner = testing::pixel(image, 2, 2);
  EXPECT_NE(centre, corner);
}

TEST(Screenshot, SimulationFolderHasOnePanelPerPickedStep) {
  THAW_SKIP_WITHOUT_X();
  testing::ScratchDir dir("shot");
  testing::write_sphere_simulation(dir.path() / "sim", 6);
  const fs::path png = dir.path() / "sim.png";
  write_simulation_screenshot(dir.path() / "sim", png);
  const auto image = testing::read_png(png);
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(dims[0], 4 * ScreenshotOptions{}.panel_size_px);  // first, two between, last
  write_simulation_screenshot(dir.path() / "sim", dir.path() / "one.png", 2);
  EXPECT_EQ(testing::read_png(dir.path() / "one.png")->GetDimensions()[0],
            ScreenshotOptions{}.panel_size_px);
  EXPECT_THROW(write_simulation_screenshot(dir.path() / "sim", png, 99), UserError);
}

TEST(Screenshot, UnwritableOutputIsUserError) {
  THAW_SKIP_WITHOUT_X();
  testing::ScratchDir dir("shot");
  meshio::write_obj(dir.path() / "ball.obj", testing::icosphere(1.0, 0));
  write_file_atomic(dir.path() / "file", "x");
  EXPECT_THROW(write_obj_screenshot(dir.path() / "ball.obj", dir.path() / "file" / "a.png"),
               UserError);
}

}  // namespace
}  // namespace thaw::inspect
