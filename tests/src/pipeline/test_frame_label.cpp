#include "src/pipeline/frame_label.h"

#include <gtest/gtest.h>

#include <vector>

namespace thaw::pipeline {
namespace {

TEST(FrameLabel, FormatsSimulatedTime) {
  EXPECT_EQ(format_sim_time_label(0), "t = 0 s");
  EXPECT_EQ(format_sim_time_label(44.6), "t = 45 s");
  EXPECT_EQ(format_sim_time_label(750), "t = 12 min 30 s");
  EXPECT_EQ(format_sim_time_label(3600 + 125), "t = 1 h 02 min");
}

TEST(FrameLabel, StampsWhiteGlyphsInsideTheImageOnly) {
  const int w = 40, h = 20;
  std::vector<float> img(w * h * 3, 0.5f);
  // Partly outside the image on purpose: must not write out of bounds (ASan checks this).
  stamp_label(img.data(), w, h, 30, 5, "t = 1", 2);
  stamp_label(img.data(), w, h, 0, 0, "1", 1);
  int white = 0, darkened = 0;
  for (int i = 0; i < w * h; ++i) {
    if (img[i * 3] == 1.0f) ++white;
    if (img[i * 3] < 0.5f) ++darkened;
  }
  EXPECT_GT(white, 5);      // the '1' glyph has 10 lit cells at scale 1
  EXPECT_GT(darkened, 20);  // the backing box
  EXPECT_EQ(label_width_px("t = 1", 2), 5 * 6 * 2);
}

}  // namespace
}  // namespace thaw::pipeline
