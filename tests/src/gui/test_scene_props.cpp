// look_catalog (src/gui/scene_props.h): the shader warm-up's child draws it so that an edit's new
// look is in Mesa's cache. Every scene an edit can make (each shape with each material kind or as
// a dielectric, each light kind, drawn at rest or quick) must give only looks the catalog has:
// a new look of the view added without a catalog actor fails here.
#include <gtest/gtest.h>
#include <vtkActor.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <string>

#include "src/gui/scene_props.h"
#include "src/gui/shell_view.h"

namespace thaw::gui {
namespace {

using render::LightDescription;
using render::MaterialDescription;
using render::ObjectDescription;

/// The looks of `props`' actors as the view draws them at rest and quick (texture off).
std::set<std::string> looks(const SceneProps& props) {
  std::set<std::string> out;
  for (std::size_t k = 0; k < props.actors.size(); ++k) {
    out.insert(look_of(props.actors[k]));
    if (!props.textures[k]) continue;
    auto quick = vtkSmartPointer<vtkActor>::New();
    quick->ShallowCopy(props.actors[k]);
    quick->SetTexture(nullptr);
    out.insert(look_of(quick));
  }
  return out;
}

render::SceneDescription one_object(ObjectDescription::Shape shape, MaterialDescription::Kind kind,
                                    render::TextureDescription::Kind texture, bool dielectric,
                                    bool smooth) {
  render::SceneDescription desc;
  desc.materials.push_back({std::string("m"), kind, {}});
  desc.materials.back().texture.kind = texture;
  ObjectDescription o;
  o.shape = shape;
  if (dielectric)
    o.inside = std::string("glass");
  else
    o.material = std::string("m");
  auto mesh = std::make_shared<render::TriangleMesh>();
  mesh->positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh->triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  o.mesh = mesh;
  o.smooth_normals = smooth;
  desc.objects.push_back(o);
  return desc;
}

TEST(LookCatalog, HoldsTheLookOfEveryObjectAndLightAnEditCanMake) {
  const render::CameraDescription camera;
  const SceneProps catalog = look_catalog(camera);
  const std::set<std::string> have = looks(catalog);
  using Kind = MaterialDescription::Kind;
  using Shape = ObjectDescription::Shape;
  for (Shape shape : {Shape::sphere, Shape::box, Shape::plane, Shape::mesh})
    for (Kind kind : {Kind::matte, Kind::metal, Kind::phong, Kind::emissive})
      for (auto texture :
           {render::TextureDescription::Kind::solid, render::TextureDescription::Kind::checker})
        for (bool dielectric : {false, true})
          for (bool smooth : {false, true}) {
            for (const std::string& look :
                 looks(make_scene_props(one_object(shape, kind, texture, dielectric, smooth), {})))
              EXPECT_TRUE(have.count(look))
                  << "shape " << static_cast<int>(shape) << " material " << static_cast<int>(kind)
                  << " texture " << static_cast<int>(texture) << " dielectric " << dielectric
                  << ": " << look;
          }
  // An OBJ file's mesh (read from disk, flat unless smooth_normals): the same looks.
  const auto obj = std::filesystem::temp_directory_path() / "thaw_test_look_catalog.obj";
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  for (Kind kind : {Kind::matte, Kind::metal, Kind::phong, Kind::emissive})
    for (bool smooth : {false, true})
      for (bool dielectric : {false, true}) {
        render::SceneDescription desc = one_object(
            Shape::mesh, kind, render::TextureDescription::Kind::solid, dielectric, smooth);
        desc.objects[0].mesh = nullptr;
        desc.objects[0].mesh_file = obj;
        for (const std::string& look : looks(make_scene_props(desc, {})))
          EXPECT_TRUE(have.count(look)) << "OBJ mesh, smooth " << smooth << ": " << look;
      }
  std::filesystem::remove(obj);
  for (auto kind : {LightDescription::Kind::point, LightDescription::Kind::sphere}) {
    render::SceneDescription desc;
    LightDescription l;
    l.kind = kind;
    l.radius = 0.1;
    desc.lights.push_back(l);
    for (const std::string& look : looks(make_scene_props(desc, {})))
      EXPECT_TRUE(have.count(look)) << "light " << static_cast<int>(kind) << ": " << look;
  }
}

}  // namespace
}  // namespace thaw::gui
