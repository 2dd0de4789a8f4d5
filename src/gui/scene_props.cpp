#include "src/gui/scene_props.h"

#include <vtkCellArray.h>
#include <vtkCubeSource.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkSphereSource.h>
#include <vtkTexture.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/geometry/obj_loader.h"
#include "src/gui/mipmapped_texture.h"
#include "src/gui/shell_step.h"
#include "src/inspect/vtk_polydata.h"

namespace thaw::gui {
namespace {

using render::ObjectDescription;
using render::RgbD;
using render::Vec3d;

/// Linear RGB as the display colour VTK takes (sRGB's gamma, roughly: the preview's PNGs are sRGB).
RgbD display(const RgbD& c) {
  RgbD d{};
  for (int k = 0; k < 3; ++k) d[k] = std::pow(std::clamp(c[k], 0.0, 1.0), 1.0 / 2.2);
  return d;
}

double dot(const Vec3d& a, const Vec3d& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3d scaled(const Vec3d& a, double s) {
  return {a[0] * s, a[1] * s, a[2] * s};
}
Vec3d plus(const Vec3d& a, const Vec3d& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
Vec3d unit(const Vec3d& a) {
  const double n = std::sqrt(dot(a, a));
  return n > 0 ? scaled(a, 1.0 / n) : Vec3d{0.0, 1.0, 0.0};
}

const render::MaterialDescription* find_material(const render::SceneDescription& desc,
                                                 const std::string& name) {
  for (const auto& m : desc.materials)
    if (m.name == name) return &m;
  return nullptr;
}

/// The checker colour at `p` (render/material/texture.h: colour 0 where the sum of the cell
/// indices is even).
RgbD checker_at(const render::TextureDescription& t, const Vec3d& p) {
  long sum = 0;
  for (int k = 0; k < 3; ++k)
    sum += static_cast<long>(std::floor((p[k] - t.checker_offset[k]) / t.checker_size));
  return t.checker_colors[static_cast<std::size_t>(sum & 1L)];
}

RgbD mean_colour(const render::TextureDescription& t) {
  if (t.kind == render::TextureDescription::Kind::solid) return t.color;
  return scaled(plus(t.checker_colors[0], t.checker_colors[1]), 0.5);
}

vtkSmartPointer<vtkActor> actor_of(vtkPolyData* data, bool smooth) {
  vtkNew<vtkPolyDataMapper> mapper;
  if (smooth) {
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(data);
    normals->SplittingOff();
    normals->ConsistencyOff();
    normals->AutoOrientNormalsOff();
    normals->Update();  // here, off the GUI thread
    vtkNew<vtkPolyData> out;
    out->ShallowCopy(normals->GetOutput());
    mapper->SetInputData(out);
  } else {
    mapper->SetInputData(data);
  }
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

/// The look of an object: its material's colour (a checker's mean where cells are not drawn),
/// metal shiny, emissive unlit; a dielectric translucent (water blue inside the puddle's medium).
void set_look(vtkActor* actor, const render::SceneDescription& desc, const ObjectDescription& o,
              const std::string& water_medium) {
  vtkProperty* p = actor->GetProperty();
  if (o.is_dielectric()) {
    const bool water = !water_medium.empty() && o.inside == water_medium;
    const RgbD c = water ? RgbD{0.16, 0.42, 0.80} : RgbD{0.80, 0.92, 1.00};
    p->SetColor(c[0], c[1], c[2]);
    p->SetOpacity(water ? 0.85 : 0.3);
    p->SetSpecular(0.6);
    p->SetSpecularPower(40);
    return;
  }
  const render::MaterialDescription* m = find_material(desc, o.material);
  if (!m) return;
  using Kind = render::MaterialDescription::Kind;
  const RgbD c = display(m->kind == Kind::emissive ? m->emission : mean_colour(m->texture));
  p->SetColor(c[0], c[1], c[2]);
  if (m->kind == Kind::emissive) {
    p->SetAmbient(1.0);
    p->SetDiffuse(0.0);
  } else if (m->kind == Kind::metal || m->kind == Kind::phong) {
    p->SetSpecular(m->kind == Kind::metal ? 0.8 : 0.4);
    p->SetSpecularPower(m->kind == Kind::metal ? 60 : std::clamp(m->shininess, 1.0, 128.0));
  }
}

/// An infinite plane as a square of `side` about `focus` projected onto it (one quad); a
/// checker material's cells as a repeated texture (two cells by two per repeat), mipmapped so the
/// cells far away blend as the render's filtered checker does rather than flicker. The cells run
/// along the plane's in-plane axes: exactly the render's 3D checker on axis-aligned planes.
struct PlaneLook {
  vtkSmartPointer<vtkPolyData> data;
  vtkSmartPointer<vtkTexture> texture;
};

PlaneLook plane_look(const ObjectDescription& o, const Vec3d& focus, double side,
                     const render::MaterialDescription* m) {
  const Vec3d n = unit(o.normal);
  // The in-plane axes: the world axis least along n, made perpendicular (axis-aligned planes get
  // axis-aligned cells, as the checker's).
  int least = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) < std::abs(n[least]) - 1e-12) least = k;
  Vec3d a{0.0, 0.0, 0.0};
  a[static_cast<std::size_t>(least)] = 1.0;
  const Vec3d u = unit(plus(a, scaled(n, -dot(a, n))));
  const Vec3d v = cross(n, u);
  const bool checker = m && m->kind != render::MaterialDescription::Kind::emissive &&
                       m->texture.kind == render::TextureDescription::Kind::checker;
  // Whole pairs of cells per side (one texture repeat each); the square is centred on the
  // focus's foot on the plane, snapped to the cell grid.
  const double cell = checker ? m->texture.checker_size : side;
  const int pairs = checker ? std::max(1, static_cast<int>(std::ceil(side / (2 * cell)))) : 1;
  const double half = checker ? pairs * cell : 0.5 * side;
  const Vec3d foot = plus(focus, scaled(n, dot(plus(o.point, scaled(focus, -1.0)), n)));
  const double fu = std::round((dot(foot, u) - dot(o.point, u)) / cell) * cell;
  const double fv = std::round((dot(foot, v) - dot(o.point, v)) / cell) * cell;
  const Vec3d centre = plus(o.point, plus(scaled(u, fu), scaled(v, fv)));
  const Vec3d origin = plus(centre, plus(scaled(u, -half), scaled(v, -half)));
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(origin.data());
  points->InsertNextPoint(plus(origin, scaled(u, 2 * half)).data());
  points->InsertNextPoint(plus(origin, plus(scaled(u, 2 * half), scaled(v, 2 * half))).data());
  points->InsertNextPoint(plus(origin, scaled(v, 2 * half)).data());
  vtkNew<vtkCellArray> quad;
  const vtkIdType ids[4] = {0, 1, 2, 3};
  quad->InsertNextCell(4, ids);
  PlaneLook look;
  look.data = vtkSmartPointer<vtkPolyData>::New();
  look.data->SetPoints(points);
  look.data->SetPolys(quad);
  vtkNew<vtkFloatArray> normals;
  normals->SetNumberOfComponents(3);
  for (int k = 0; k < 4; ++k) normals->InsertNextTuple3(n[0], n[1], n[2]);
  look.data->GetPointData()->SetNormals(normals);
  if (!checker) return look;
  vtkNew<vtkFloatArray> tcoords;
  tcoords->SetNumberOfComponents(2);
  const float r = static_cast<float>(pairs);
  tcoords->InsertNextTuple2(0, 0);
  tcoords->InsertNextTuple2(r, 0);
  tcoords->InsertNextTuple2(r, r);
  tcoords->InsertNextTuple2(0, r);
  look.data->GetPointData()->SetTCoords(tcoords);
  // The texture: 2 x 2 cells of 32 x 32 texels (so linear filtering keeps the cells' edges
  // sharp up close). Which colour the first cell has: the render's checker at its centre.
  const Vec3d lift = scaled(n, 1e-6 * cell);  // off the plane, as a hit point's offset
  const Vec3d first = plus(plus(origin, lift), plus(scaled(u, 0.5 * cell), scaled(v, 0.5 * cell)));
  const RgbD c00 = display(checker_at(m->texture, first));
  const RgbD c10 = display(checker_at(m->texture, plus(first, scaled(u, cell))));
  constexpr int kTexels = 32;
  vtkNew<vtkImageData> image;
  image->SetDimensions(2 * kTexels, 2 * kTexels, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  for (int y = 0; y < 2 * kTexels; ++y)
    for (int x = 0; x < 2 * kTexels; ++x) {
      const RgbD& c = ((x / kTexels + y / kTexels) % 2 == 0) ? c00 : c10;
      auto* px = static_cast<unsigned char*>(image->GetScalarPointer(x, y, 0));
      for (int k = 0; k < 3; ++k)
        px[k] = static_cast<unsigned char>(std::lround(255.0 * c[static_cast<std::size_t>(k)]));
    }
  auto texture = vtkSmartPointer<MipmappedTexture>::New();  // its levels made here, off the GUI
  texture->set_image(image);                                // thread
  texture->RepeatOn();
  texture->InterpolateOn();
  texture->MipmapOn();
  look.texture = texture;
  return look;
}

vtkSmartPointer<vtkPolyData> sphere_data(const Vec3d& centre, double radius) {
  vtkNew<vtkSphereSource> s;
  s->SetCenter(centre.data());
  s->SetRadius(radius);
  s->SetThetaResolution(40);
  s->SetPhiResolution(24);
  s->Update();
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->ShallowCopy(s->GetOutput());
  return data;
}

vtkSmartPointer<vtkPolyData> mesh_data(const render::SceneDescription& desc,
                                       const ObjectDescription& o) {
  render::TriangleMesh mesh;
  if (o.mesh) {
    mesh = *o.mesh;
  } else {
    const auto path = o.mesh_file.is_absolute() ? o.mesh_file : desc.base_dir / o.mesh_file;
    mesh = render::load_obj(path);
  }
  render::transform_mesh(mesh, o.scale, o.translate);
  return inspect::to_polydata(to_view_mesh(mesh));
}

void append(std::string& key, const char* name, const Vec3d& v) {
  char text[96];
  std::snprintf(text, sizeof text, " %s %.17g %.17g %.17g", name, v[0], v[1], v[2]);
  key += text;
}
void append(std::string& key, const char* name, double x) {
  char text[48];
  std::snprintf(text, sizeof text, " %s %.17g", name, x);
  key += text;
}

bool skipped(const ObjectDescription& o, const std::vector<const render::TriangleMesh*>& skip) {
  return o.mesh && std::find(skip.begin(), skip.end(), o.mesh.get()) != skip.end();
}

/// The shell's water medium: the inside of the skipped inner surface (the puddle shares it).
std::string water_medium(const render::SceneDescription& desc,
                         const std::vector<const render::TriangleMesh*>& skip) {
  std::string name;
  for (const auto& o : desc.objects)
    if (skipped(o, skip) && o.is_dielectric()) name = o.inside;  // the inner surface comes last
  return name;
}

}  // namespace

namespace {

/// What one object's actor depends on: its shape and placement, its material's look, and for a
/// plane the camera it is drawn about.
std::string object_key(const render::SceneDescription& desc, const ObjectDescription& o) {
  std::string key = "object " + std::to_string(static_cast<int>(o.shape)) + " " + o.material + " " +
                    o.inside + " " + o.mesh_file.string();
  append(key, "c", o.center);
  append(key, "r", o.radius);
  append(key, "min", o.box_min);
  append(key, "max", o.box_max);
  append(key, "p", o.point);
  append(key, "n", o.normal);
  append(key, "s", o.scale);
  append(key, "t", o.translate);
  if (o.mesh) {  // in memory (the puddle): its size and extreme vertices
    append(key, "tri", static_cast<double>(o.mesh->triangles.size()));
    if (!o.mesh->positions.empty()) {
      const auto& a = o.mesh->positions.front();
      const auto& b = o.mesh->positions.back();
      append(key, "v0", Vec3d{a.x, a.y, a.z});
      append(key, "v1", Vec3d{b.x, b.y, b.z});
    }
  }
  if (const render::MaterialDescription* m = find_material(desc, o.material)) {
    key += " material " + std::to_string(static_cast<int>(m->kind)) + " " +
           std::to_string(static_cast<int>(m->texture.kind));
    append(key, "c", m->texture.color);
    append(key, "c0", m->texture.checker_colors[0]);
    append(key, "c1", m->texture.checker_colors[1]);
    append(key, "size", m->texture.checker_size);
    append(key, "o", m->texture.checker_offset);
    append(key, "e", m->emission);
    append(key, "sh", m->shininess);
  }
  if (o.shape == ObjectDescription::Shape::plane) {  // drawn about the camera's focus
    append(key, "focus", desc.camera.look_at);
    append(key, "eye", desc.camera.position);
  }
  return key;
}

std::string light_key(const render::SceneDescription& desc, const render::LightDescription& l) {
  std::string key = "light " + std::to_string(static_cast<int>(l.kind));
  append(key, "p", l.position);
  append(key, "r", l.radius);
  append(key, "c", l.color);
  if (l.kind == render::LightDescription::Kind::point) {  // sized by the camera's distance
    append(key, "focus", desc.camera.look_at);
    append(key, "eye", desc.camera.position);
  }
  return key;
}

}  // namespace

std::string scene_props_key(const render::SceneDescription& desc,
                            const std::vector<const render::TriangleMesh*>& skip) {
  std::string key;
  for (const auto& o : desc.objects)
    if (!skipped(o, skip)) key += object_key(desc, o) + "\n";
  for (const auto& l : desc.lights) key += light_key(desc, l) + "\n";
  return key;
}

namespace {

/// An object's geometry as the view draws it: a plane as a square about the camera's focus, with
/// its checker as a texture.
struct ObjectGeometry {
  vtkSmartPointer<vtkPolyData> data;
  vtkSmartPointer<vtkTexture> texture;
  bool smooth = false;
};

ObjectGeometry object_geometry(const render::SceneDescription& desc, const ObjectDescription& o,
                               const Vec3d& focus, double distance) {
  ObjectGeometry g;
  switch (o.shape) {
    case ObjectDescription::Shape::sphere:
      g.data = sphere_data(o.center, o.radius);
      break;
    case ObjectDescription::Shape::box: {
      vtkNew<vtkCubeSource> box;
      box->SetBounds(o.box_min[0], o.box_max[0], o.box_min[1], o.box_max[1], o.box_min[2],
                     o.box_max[2]);
      box->Update();
      g.data = vtkSmartPointer<vtkPolyData>::New();
      g.data->ShallowCopy(box->GetOutput());
      break;
    }
    case ObjectDescription::Shape::plane: {
      // Large against the camera's distance: the render's plane reaches the horizon.
      PlaneLook look = plane_look(o, focus, 16.0 * distance,
                                  o.is_dielectric() ? nullptr : find_material(desc, o.material));
      g.data = look.data;
      g.texture = look.texture;
      break;
    }
    case ObjectDescription::Shape::mesh:
      g.data = mesh_data(desc, o);
      g.smooth = o.smooth_normals || o.mesh != nullptr;
      break;
  }
  return g;
}

/// A point light as a small ball (3 % of the camera's distance), a sphere light as itself; both
/// unlit in the light's colour.
vtkSmartPointer<vtkActor> light_actor(const render::LightDescription& l, double distance) {
  const bool sphere = l.kind == render::LightDescription::Kind::sphere;
  vtkSmartPointer<vtkActor> actor =
      actor_of(sphere_data(l.position, sphere ? l.radius : 0.03 * distance), false);
  actor->GetMapper()->ScalarVisibilityOff();
  const RgbD c = display(l.color);
  vtkProperty* p = actor->GetProperty();
  p->SetColor(0.5 + 0.5 * c[0], 0.5 + 0.5 * c[1], 0.3 * c[2]);  // yellowish, as a lamp
  p->SetAmbient(1.0);
  p->SetDiffuse(0.0);
  p->SetOpacity(sphere ? 0.6 : 1.0);
  return actor;
}

/// The actor `previous` made for `key`, its texture and quick colour appended to `props`; null
/// when it has none. An actor whose key is unchanged is taken over as it is (its triangles and
/// texture uploaded once): after a slider move only the puddle's actor is new.
vtkSmartPointer<vtkActor> reuse_actor(const SceneProps* previous, const std::string& key,
                                      SceneProps& props) {
  if (!previous) return nullptr;
  for (std::size_t k = 0; k < previous->actor_keys.size(); ++k)
    if (previous->actor_keys[k] == key) {
      props.textures.push_back(previous->textures[k]);
      props.quick_colors.push_back(previous->quick_colors[k]);
      return previous->actors[k];
    }
  return nullptr;
}

/// Appends a new actor of `o` with its texture and the colour it is drawn quick in.
void add_object_actor(const render::SceneDescription& desc, const ObjectDescription& o,
                      const Vec3d& focus, double distance, const std::string& water,
                      SceneProps& props) {
  const ObjectGeometry g = object_geometry(desc, o, focus, distance);
  vtkSmartPointer<vtkActor> actor = actor_of(g.data, g.smooth);
  set_look(actor, desc, o, water);
  actor->GetMapper()->ScalarVisibilityOff();
  props.textures.push_back(g.texture);
  const render::MaterialDescription* material =
      o.is_dielectric() ? nullptr : find_material(desc, o.material);
  props.quick_colors.push_back(material ? display(mean_colour(material->texture))
                                        : RgbD{1.0, 1.0, 1.0});
  if (g.texture) {
    actor->SetTexture(g.texture);
    actor->GetProperty()->SetColor(1.0, 1.0, 1.0);  // the texture's colours as they are
  }
  props.actors.push_back(actor);
}

/// Appends a new actor of the light `l`.
void add_light_actor(const render::LightDescription& l, double distance, SceneProps& props) {
  props.textures.push_back(nullptr);
  props.quick_colors.push_back({1.0, 1.0, 1.0});
  props.actors.push_back(light_actor(l, distance));
}

}  // namespace

SceneProps make_scene_props(const render::SceneDescription& desc,
                            const std::vector<const render::TriangleMesh*>& skip,
                            const SceneProps* previous) {
  SceneProps props;
  props.camera = desc.camera;
  props.key = scene_props_key(desc, skip);
  const Vec3d focus = desc.camera.look_at;
  const Vec3d to_eye = plus(desc.camera.position, scaled(focus, -1.0));
  const double distance = std::max(1e-3, std::sqrt(dot(to_eye, to_eye)));
  const std::string water = water_medium(desc, skip);
  for (const auto& o : desc.objects) {
    if (skipped(o, skip)) continue;
    const std::string key = object_key(desc, o);
    ++props.objects;
    props.actor_keys.push_back(key);
    if (auto actor = reuse_actor(previous, key, props))
      props.actors.push_back(actor);
    else
      add_object_actor(desc, o, focus, distance, water, props);
  }
  for (const auto& l : desc.lights) {
    const std::string key = light_key(desc, l);
    ++props.lights;
    props.actor_keys.push_back(key);
    if (auto actor = reuse_actor(previous, key, props))
      props.actors.push_back(actor);
    else
      add_light_actor(l, distance, props);
  }
  return props;
}

}  // namespace thaw::gui
