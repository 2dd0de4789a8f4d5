// mip_levels (src/gui/mipmapped_texture.h): the 3D view's floor texture's levels, made on the CPU
// instead of by glGenerateMipmap. Each level is the previous one's 2x2 box average, rounded to
// the nearest byte: the expected values below are those averages worked out by hand (exact
// integers, so the comparisons are exact).
#include <gtest/gtest.h>

#include <vector>

#include "src/gui/mipmapped_texture.h"

namespace thaw::gui {
namespace {

TEST(MipLevels, EachLevelIsTheRoundedTwoByTwoAverageOfTheOneAbove) {
  // 4 x 2 pixels of one byte: rows bottom-up {0, 10, 20, 31}, {2, 12, 21, 30}.
  MipLevel base{4, 2, {0, 10, 20, 31, 2, 12, 21, 30}};
  const std::vector<MipLevel> levels = mip_levels(base, 1);
  ASSERT_EQ(levels.size(), 2u);  // 2 x 1, then 1 x 1
  EXPECT_EQ(levels[0].width, 2);
  EXPECT_EQ(levels[0].height, 1);
  // (0 + 10 + 2 + 12) / 4 = 6; (20 + 31 + 21 + 30) / 4 = 25.5 -> 26 (rounded half up)
  EXPECT_EQ(levels[0].pixels, (std::vector<unsigned char>{6, 26}));
  // a side already 1: the two pixels averaged, (6 + 26) / 2 = 16
  EXPECT_EQ(levels[1].width, 1);
  EXPECT_EQ(levels[1].height, 1);
  EXPECT_EQ(levels[1].pixels, (std::vector<unsigned char>{16}));
}

TEST(MipLevels, TheFloorCheckerEndsInItsFourCellsThenTheirMean) {
  // The floor's texture (scene_props.cpp): 2 x 2 cells of 32 x 32 RGB texels.
  const unsigned char a[3] = {200, 60, 60}, b[3] = {240, 240, 235};
  MipLevel base{64, 64, std::vector<unsigned char>(64 * 64 * 3)};
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c)
        base.pixels[(static_cast<std::size_t>(y) * 64 + x) * 3 + c] =
            ((x / 32 + y / 32) % 2 == 0) ? a[c] : b[c];
  const std::vector<MipLevel> levels = mip_levels(base, 3);
  ASSERT_EQ(levels.size(), 6u);  // 32, 16, 8, 4, 2, 1 texels across
  const MipLevel& cells = levels[4];
  ASSERT_EQ(cells.width, 2);
  // every texel of a cell averages to the cell's colour exactly (uniform 2x2 blocks)
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(cells.pixels[0 * 3 + c], a[c]);  // (0, 0)
    EXPECT_EQ(cells.pixels[1 * 3 + c], b[c]);  // (1, 0)
    EXPECT_EQ(cells.pixels[2 * 3 + c], b[c]);  // (0, 1)
    EXPECT_EQ(cells.pixels[3 * 3 + c], a[c]);  // (1, 1)
  }
  // the mean of two a and two b: (2 * 200 + 2 * 240) / 4 = 220, (2 * 60 + 2 * 240) / 4 = 150,
  // (2 * 60 + 2 * 235) / 4 = 147.5 -> 148
  EXPECT_EQ(levels[5].pixels, (std::vector<unsigned char>{220, 150, 148}));
}

TEST(MipLevels, OneTexelHasNoLevelsBelow) {
  EXPECT_TRUE(mip_levels(MipLevel{1, 1, {7}}, 1).empty());
}

}  // namespace
}  // namespace thaw::gui
