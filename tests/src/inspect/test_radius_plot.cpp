// End-to-end tests of src/inspect/radius_plot (needs X: a display or Xvfb; skipped without).
#include "src/inspect/radius_plot.h"

#include <gtest/gtest.h>

#include "base/error.h"
#include "tests/src/inspect/render_check.h"
#include "tests/src/inspect/test_meshes.h"

namespace thaw::inspect {
namespace {

TEST(RadiusPlot, WritesAChartOfTheRequestedSize) {
  THAW_SKIP_WITHOUT_X();
  testing::ScratchDir dir("plot");
  testing::write_sphere_simulation(dir.path() / "sim", 5);
  const auto png = dir.path() / "plot.png";
  write_radius_plot(dir.path() / "sim", png);
  const auto image = testing::read_png(png);
  int dims[3];
  image->GetDimensions(dims);
  const PlotOptions defaults;
  EXPECT_EQ(dims[0], defaults.width_px);
  EXPECT_EQ(dims[1], defaults.height_px);
  // A white page with lines, text and axes on it: some but not most pixels are dark or coloured.
  long inked = 0;
  for (int y = 0; y < dims[1]; y += 2)
    for (int x = 0; x < dims[0]; x += 2) {
      const auto p = testing::pixel(image, x, y);
      if (p[0] < 200 || p[1] < 200 || p[2] < 200) ++inked;
    }
  const double fraction = static_cast<double>(inked) / ((dims[0] / 2) * (dims[1] / 2));
  EXPECT_GT(fraction, 0.005);
  EXPECT_LT(fraction, 0.5);
}

TEST(RadiusPlot, NoRowsIsUserError) {
  EXPECT_THROW(write_radius_plot(std::vector<sim::InterfaceRecord>{}, "x.png"), UserError);
}

}  // namespace
}  // namespace thaw::inspect
