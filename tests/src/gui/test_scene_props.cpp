// make_scene_props (src/gui/scene_props.h): one actor per object and light of the frame's scene
// (the shell's own surfaces left out), a texture only where cells are drawn (a checker plane),
// and the actors of unchanged objects and lights taken over from the previous props, so that the
// view's render thread keeps their uploaded geometry.
#include <gtest/gtest.h>
#include <vtkActor.h>

#include <memory>
#include <string>

#include "src/gui/scene_props.h"

namespace thaw::gui {
namespace {

using render::LightDescription;
using render::MaterialDescription;
using render::ObjectDescription;

/// A grey matte sphere, a checker plane and a point light.
render::SceneDescription small_scene() {
  render::SceneDescription desc;
  desc.materials.push_back({std::string("grey"), MaterialDescription::Kind::matte, {}});
  desc.materials.push_back({std::string("floor"), MaterialDescription::Kind::matte, {}});
  desc.materials.back().texture.kind = render::TextureDescription::Kind::checker;
  ObjectDescription sphere;
  sphere.shape = ObjectDescription::Shape::sphere;
  sphere.center = {0.1, 0.0, 0.0};
  sphere.radius = 0.02;
  sphere.material = std::string("grey");
  desc.objects.push_back(sphere);
  ObjectDescription plane;
  plane.shape = ObjectDescription::Shape::plane;
  plane.point = {0.0, 0.0, 0.0};
  plane.normal = {0.0, 1.0, 0.0};
  plane.material = std::string("floor");
  desc.objects.push_back(plane);
  LightDescription light;
  light.kind = LightDescription::Kind::point;
  light.position = {0.0, 0.3, 0.2};
  desc.lights.push_back(light);
  desc.camera.position = {0.0, 0.1, 0.3};
  desc.camera.look_at = {0.0, 0.0, 0.0};
  return desc;
}

TEST(SceneProps, OneActorPerObjectAndLightTexturedWhereCellsAreDrawn) {
  const SceneProps props = make_scene_props(small_scene(), {});
  EXPECT_EQ(props.objects, 2u);
  EXPECT_EQ(props.lights, 1u);
  ASSERT_EQ(props.actors.size(), 3u);
  ASSERT_EQ(props.textures.size(), 3u);
  ASSERT_EQ(props.quick_colors.size(), 3u);
  EXPECT_FALSE(props.textures[0]);  // the solid sphere
  EXPECT_TRUE(props.textures[1]);   // the checker plane
  EXPECT_FALSE(props.textures[2]);  // the light's glyph
  // The plane drawn quick is the mean of its grey cells: a grey strictly between them.
  const auto& q = props.quick_colors[1];
  EXPECT_DOUBLE_EQ(q[0], q[1]);
  EXPECT_DOUBLE_EQ(q[1], q[2]);
  EXPECT_GT(q[0], 0.0);
  EXPECT_LT(q[0], 1.0);
  for (const auto& a : props.actors) EXPECT_TRUE(a->GetMapper());
}

TEST(SceneProps, UnchangedObjectsKeepTheirActorsAndMovedOnesGetNewOnes) {
  render::SceneDescription desc = small_scene();
  const SceneProps first = make_scene_props(desc, {});
  desc.objects[0].center = {0.2, 0.0, 0.0};  // the sphere moved; the plane and light not
  const SceneProps second = make_scene_props(desc, {}, &first);
  ASSERT_EQ(second.actors.size(), 3u);
  EXPECT_NE(second.actors[0].Get(), first.actors[0].Get());
  EXPECT_EQ(second.actors[1].Get(), first.actors[1].Get());
  EXPECT_EQ(second.textures[1].Get(), first.textures[1].Get());
  EXPECT_EQ(second.actors[2].Get(), first.actors[2].Get());
  EXPECT_NE(second.key, first.key);
  // Nothing changed: every actor taken over, the same key.
  const SceneProps third = make_scene_props(desc, {}, &second);
  EXPECT_EQ(third.key, second.key);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(third.actors[k].Get(), second.actors[k].Get());
}

TEST(SceneProps, TheShellsOwnSurfacesAreLeftOut) {
  render::SceneDescription desc = small_scene();
  auto mesh = std::make_shared<render::TriangleMesh>();
  mesh->positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh->triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  ObjectDescription shell;
  shell.shape = ObjectDescription::Shape::mesh;
  shell.mesh = mesh;
  shell.material = std::string("grey");
  desc.objects.push_back(shell);
  EXPECT_EQ(make_scene_props(desc, {}).objects, 3u);
  const SceneProps without = make_scene_props(desc, {mesh.get()});
  EXPECT_EQ(without.objects, 2u);
  EXPECT_EQ(without.actors.size(), 3u);
}

}  // namespace
}  // namespace thaw::gui
