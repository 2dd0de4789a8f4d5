// Tests render/material/texture.h: the 3D checker parity and offset convention of POV-Ray.
#include "render/material/texture.h"

#include <gtest/gtest.h>

namespace thaw::render {
namespace {

TEST(Texture, CheckerParityAndOffset) {
  Texture t;
  t.kind = Texture::Kind::checker;
  t.color0 = Rgb{1, 0, 0};
  t.color1 = Rgb{0, 0, 1};
  t.size = 0.5f;
  t.offset = Vec3{0, 0.25f, 0};
  // floor(x/0.5) + floor((y-0.25)/0.5) + floor(z/0.5): (0.1, -1, 0.1) -> 0 - 3 + 0 = -3, odd.
  EXPECT_EQ(t.eval({0.1f, -1.0f, 0.1f}), t.color1);
  EXPECT_EQ(t.eval({0.6f, -1.0f, 0.1f}), t.color0);
  EXPECT_EQ(t.eval({-0.1f, -1.0f, 0.1f}), t.color0);
  t.kind = Texture::Kind::solid;
  EXPECT_EQ(t.eval({0.1f, -1.0f, 0.1f}), t.color0);
}

}  // namespace
}  // namespace thaw::render
