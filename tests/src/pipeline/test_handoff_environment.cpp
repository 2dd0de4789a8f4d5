#include "src/pipeline/handoff_environment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace thaw::pipeline {
namespace {

void expect_direction(double u, double v, float x, float y, float z) {
  const render::Vec3 d = blender_latlong_direction(u, v);
  EXPECT_NEAR(d.x, x, 1e-6) << u << " " << v;
  EXPECT_NEAR(d.y, y, 1e-6) << u << " " << v;
  EXPECT_NEAR(d.z, z, 1e-6) << u << " " << v;
}

TEST(HandoffEnvironment, BlendersLatLongLayoutInThawsAxes) {
  // Blender's (x, y, z) is thaw's (x, z, -y): the image centre looks along +x, a quarter to the
  // left (u = 0.25) along Blender's +y = thaw's -z, the top row at thaw's +y (up).
  expect_direction(0.5, 0.5, 1, 0, 0);
  expect_direction(0.25, 0.5, 0, 0, -1);
  expect_direction(0.75, 0.5, 0, 0, 1);
  expect_direction(0.0, 0.5, -1, 0, 0);
  expect_direction(0.5, 1.0, 0, 1, 0);
  expect_direction(0.5, 0.0, 0, -1, 0);
}

TEST(HandoffEnvironment, BakedPanelIsWhereItsDirectionLooks) {
  render::Environment env;
  env.kind = render::Environment::Kind::sky;
  env.zenith = env.horizon = env.ground = render::Rgb(0.1f, 0.1f, 0.1f);
  render::EnvironmentPanel panel;
  panel.centre = render::Vec3(0, 0, -1);  // thaw's -z: Blender's +y, u = 0.25, v = 0.5
  panel.right = render::Vec3(1, 0, 0);
  panel.top = render::Vec3(0, 1, 0);
  panel.half_width = panel.half_height = 0.2f;
  panel.edge = 0.01f;
  panel.radiance = render::Rgb(2.0f, 1.0f, 0.5f);
  env.panels.push_back(panel);
  const auto path = std::filesystem::temp_directory_path() / "thaw_test_env.hdr";
  const int w = 64, h = 32;
  write_environment_hdr(env, path, w);
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  const std::string text = s.str();
  std::filesystem::remove(path);
  const std::string size_line = "-Y 32 +X 64\n";
  const auto at = text.find(size_line);
  ASSERT_NE(at, std::string::npos);
  const std::size_t data = at + size_line.size();
  ASSERT_EQ(text.size(), data + 4u * w * h);
  const auto texel = [&](int col, int row) {
    const auto* p = reinterpret_cast<const unsigned char*>(&text[data + 4 * (row * w + col)]);
    const double f = std::ldexp(1.0, p[3] - 136);  // (mantissa + 0.5) 2^(e - 136) is the centre
    return std::array<double, 3>{(p[0] + 0.5) * f, (p[1] + 0.5) * f, (p[2] + 0.5) * f};
  };
  const auto in_panel = texel(w / 4, h / 2);  // u = 0.25 + half a pixel, v = 0.5 - half
  const auto outside = texel(3 * w / 4, h / 2);
  EXPECT_NEAR(in_panel[0], 2.1, 2.1 / 128);  // RGBE: 8-bit mantissas of the largest channel
  EXPECT_NEAR(in_panel[1], 1.1, 2.1 / 128);
  EXPECT_NEAR(in_panel[2], 0.6, 2.1 / 128);
  for (double c : outside) EXPECT_NEAR(c, 0.1, 0.1 / 128);
}

}  // namespace
}  // namespace thaw::pipeline
