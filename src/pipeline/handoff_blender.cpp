#include "src/pipeline/handoff_blender.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>

#include "base/atomic_file.h"
#include "base/check.h"
#include "base/obj_writer.h"
#include "embedded/kBlenderSceneScript.h"
#include "render/geometry/obj_loader.h"
#include "render/media/ior_model.h"
#include "render/scene/scene.h"
#include "src/pipeline/frame_camera.h"
#include "src/pipeline/frame_scene.h"
#include "src/pipeline/handoff_camera.h"
#include "src/pipeline/handoff_environment.h"
#include "src/pipeline/handoff_paraview.h"
#include "thaw_version.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

/// Width [px] of the baked environment: 0.35 degree pixels, 2 MB.
constexpr int kEnvironmentWidth = 1024;
/// Half-size [m] of the square that stands for an endless plane.
constexpr double kPlaneExtentM = 200.0;

json v3(const std::array<double, 3>& v) {
  return json{v[0], v[1], v[2]};
}

/// "shell outer surface" -> "shell_outer_surface"; characters other than letters and digits
/// become underscores.
std::string slug(const std::string& label) {
  std::string s;
  for (char c : label) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return s;
}

/// The material of a surface between two media: "thaw ice | vacuum", or with its roughness
/// "thaw ice | vacuum, roughness 0.3".
std::string interface_name(const render::ObjectDescription& o) {
  std::string name = "thaw " + o.inside + " | " + o.outside;
  if (o.roughness > 0) {
    char r[48];
    std::snprintf(r, sizeof r, ", roughness %.6g", o.roughness);
    name += r;
  }
  return name;
}

struct Interface {
  std::string inside, outside;
  double roughness = 0;
};

const render::media::Medium* find_medium(const render::Scene& scene, const std::string& name) {
  for (const auto& m : scene.media())
    if (m.name == name) return &m.optics;
  return nullptr;
}

meshio::TriangleMesh to_meshio(const render::TriangleMesh& m) {
  meshio::TriangleMesh out;
  out.vertices.reserve(m.positions.size());
  for (const auto& p : m.positions) out.vertices.push_back({p.x, p.y, p.z});
  out.triangles.reserve(m.triangles.size());
  for (const auto& t : m.triangles) out.triangles.push_back({t[0], t[1], t[2]});
  return out;
}

json texture_json(const render::TextureDescription& t) {
  json j;
  j["kind"] = t.kind == render::TextureDescription::Kind::checker ? "checker" : "solid";
  j["color"] = v3(t.color);
  j["checker_colors"] = {v3(t.checker_colors[0]), v3(t.checker_colors[1])};
  j["checker_size_m"] = t.checker_size;
  j["checker_offset_m"] = v3(t.checker_offset);
  return j;
}

json material_json(const render::MaterialDescription& m) {
  using K = render::MaterialDescription::Kind;
  json j;
  j["name"] = m.name;
  j["kind"] = m.kind == K::matte   ? "matte"
              : m.kind == K::metal ? "metal"
              : m.kind == K::phong ? "phong"
                                   : "emissive";
  j["texture"] = texture_json(m.texture);
  // thaw's roughness is Blender's (GGX alpha = roughness^2 in both). A smooth phong material's
  // highlight: Phong exponent n to Beckmann alpha = sqrt(2 / (n + 2)) (Walter et al. 2007,
  // eq. 33), roughness = sqrt(alpha). A smooth metal is a mirror.
  j["roughness"] = m.roughness > 0      ? m.roughness
                   : m.kind == K::phong ? std::sqrt(std::sqrt(2.0 / (m.shininess + 2.0)))
                                        : 0.0;
  const double e = m.emission_intensity;
  j["emission"] = {m.emission[0] * e, m.emission[1] * e, m.emission[2] * e};
  return j;
}

}  // namespace

double blender_light_power_w(double intensity, bool inverse_square, double reference_distance_m) {
  const double pi2 = std::numbers::pi * std::numbers::pi;
  const double d2 = inverse_square ? 1.0 : reference_distance_m * reference_distance_m;
  return 4.0 * pi2 * intensity * d2;
}

void write_scene_handoff(const SceneHandoffInput& in) {
  THAW_CHECK(in.framed && in.meshes && in.water,
             "the hand-off needs the run's scenario and meshes");
  const RunScenario& sc = *in.framed;
  const mesh::MeshManifest& meshes = *in.meshes;
  if (meshes.steps.empty()) return;
  const fs::path handoff = in.run_dir / "handoff";
  fs::create_directories(handoff / "meshes");
  const auto rel = [&](const fs::path& p) { return fs::relative(p, in.run_dir).generic_string(); };

  json required = json::array();
  json frames = json::array();
  // Surfaces in order of first appearance: label -> index into `surfaces`.
  std::map<std::string, std::size_t> surface_of;
  json surfaces = json::array();
  std::map<std::string, Interface> interfaces;  // by material name
  const std::size_t static_objects = sc.scene.objects.size();
  const std::size_t frame_count = meshes.steps.size();
  std::optional<render::Scene> first;  // frame 0, built: media, environment
  for (std::size_t k = 0; k < frame_count; ++k) {
    const mesh::StepRecord& step = meshes.steps[k];
    FrameShell shell;
    if (step.outer.file) {
      required.push_back({rel(in.mesh_dir / *step.outer.file), "mesh"});
      shell.outer =
          std::make_shared<render::TriangleMesh>(render::load_obj(in.mesh_dir / *step.outer.file));
    }
    if (step.inner.file) {
      required.push_back({rel(in.mesh_dir / *step.inner.file), "mesh"});
      shell.inner =
          std::make_shared<render::TriangleMesh>(render::load_obj(in.mesh_dir / *step.inner.file));
    }
    shell.outer_radius_m = step.outer_radius_m;
    const render::SceneDescription desc =
        frame_scene(sc, meshes.geometry, shell, in.water->at(static_cast<std::size_t>(step.step)));
    if (k == 0) first = render::build_scene(desc);
    frames.push_back({{"frame", k}, {"step", step.step}, {"time_s", step.time_s}});
    for (std::size_t i = static_objects; i < desc.objects.size(); ++i) {
      const render::ObjectDescription& o = desc.objects[i];
      auto [it, added] = surface_of.emplace(o.label, surfaces.size());
      if (added) {
        json s;
        s["object"] = slug(o.label);
        s["label"] = o.label;
        s["inside"] = o.inside;
        s["outside"] = o.outside;
        s["material"] = interface_name(o);
        s["frames"] = json::array();
        surfaces.push_back(s);
        interfaces[interface_name(o)] = {o.inside, o.outside, o.roughness};
      }
      json& s = surfaces[it->second];
      while (s["frames"].size() < k) s["frames"].push_back(nullptr);
      std::string file;
      if (o.mesh == shell.outer) {
        file = rel(in.mesh_dir / *step.outer.file);
      } else if (o.mesh == shell.inner) {
        file = rel(in.mesh_dir / *step.inner.file);
      } else {  // made for the frame only (the puddle): kept here, the run's one copy
        THAW_CHECK(o.mesh != nullptr, "a frame's own surface is a mesh in memory");
        char name[160];
        std::snprintf(name, sizeof name, "%s_%06zu.obj", slug(o.label).c_str(), k);
        char comment[200];
        std::snprintf(comment, sizeof comment, "thaw run: frame %zu, t = %.17g s, %s [m], y up", k,
                      step.time_s, o.label.c_str());
        meshio::write_obj(handoff / "meshes" / name, to_meshio(*o.mesh), comment);
        file = rel(handoff / "meshes" / name);
        required.push_back({file, in.stage});
      }
      s["frames"].push_back({{"file", file}, {"translate_m", v3(o.translate)}, {"scale", o.scale}});
    }
  }
  for (json& s : surfaces)
    while (s["frames"].size() < frame_count) s["frames"].push_back(nullptr);

  json data;
  data["thaw_version"] = THAW_VERSION_STRING;
  data["scenario"] = sc.source_name;
  data["image"] = {{"width", sc.scene.image.width},
                   {"height", sc.scene.image.height},
                   {"max_depth", sc.scene.image.max_depth},
                   {"exposure_stops", sc.scene.image.exposure}};
  data["fps"] = sc.film.film_fps();
  data["frames"] = frames;
  data["surfaces"] = surfaces;
  data["ice_surface"] = "";
  for (const json& s : surfaces)
    if (s["inside"] == sc.shell.ice_medium && s["outside"] == sc.shell.outside_medium)
      data["ice_surface"] = s["object"];
  const render::CameraDescription& cam = sc.scene.camera;
  data["camera"] = {{"position_m", v3(cam.position)},
                    {"look_at_m", v3(cam.look_at)},
                    {"up", v3(cam.up)},
                    {"vertical_fov_deg", cam.vertical_fov_deg}};
  json lights = json::array();
  for (const render::LightDescription& l : sc.scene.lights) {
    const std::array<double, 3> d{l.position[0] - cam.look_at[0], l.position[1] - cam.look_at[1],
                                  l.position[2] - cam.look_at[2]};
    const bool inverse_square = l.falloff == render::LightDescription::Falloff::inverse_square;
    lights.push_back(
        {{"position_m", v3(l.position)},
         {"color", v3(l.color)},
         {"radius_m", l.kind == render::LightDescription::Kind::sphere ? l.radius : 0.0},
         {"power_w", blender_light_power_w(l.intensity, inverse_square,
                                           std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]))}});
  }
  data["lights"] = lights;
  if (sc.scene.environment.kind == render::EnvironmentDescription::Kind::constant) {
    data["environment"] = {{"kind", "color"}, {"color", v3(sc.scene.image.background)}};
  } else {
    write_environment_hdr(first->environment(), handoff / "environment.hdr", kEnvironmentWidth);
    data["environment"] = {{"kind", "map"}, {"file", "handoff/environment.hdr"}};
    required.push_back({"handoff/environment.hdr", in.stage});
  }
  json materials = json::array();
  for (const auto& m : sc.scene.materials) materials.push_back(material_json(m));
  data["materials"] = materials;
  json objects = json::array();
  for (std::size_t i = 0; i < static_objects; ++i) {
    const render::ObjectDescription& o = sc.scene.objects[i];
    using S = render::ObjectDescription::Shape;
    json j;
    const std::string shape = o.shape == S::mesh     ? "mesh"
                              : o.shape == S::sphere ? "sphere"
                              : o.shape == S::box    ? "box"
                                                     : "plane";
    j["object"] = shape + "_" + std::to_string(i);  // scenario objects: "plane_0", "sphere_1"
    j["shape"] = shape;
    j["center_m"] = v3(o.center);
    j["radius_m"] = o.radius;
    j["min_m"] = v3(o.box_min);
    j["max_m"] = v3(o.box_max);
    j["point_m"] = v3(o.point);
    j["normal"] = v3(o.normal);
    j["extent_m"] = kPlaneExtentM;
    j["file"] = o.mesh_file.empty()
                    ? ""
                    : fs::absolute(sc.scene.base_dir / o.mesh_file).lexically_normal().string();
    j["scale"] = o.scale;
    j["translate_m"] = v3(o.translate);
    if (o.is_dielectric()) {
      j["material"] = interface_name(o);
      interfaces[interface_name(o)] = {o.inside, o.outside, o.roughness};
    } else {
      j["material"] = o.material;
    }
    objects.push_back(j);
  }
  data["objects"] = objects;
  json media_pairs = json::array();
  for (const auto& [name, face] : interfaces) {
    const auto* inside = find_medium(*first, face.inside);
    const auto* outside = find_medium(*first, face.outside);
    THAW_CHECK(inside && outside, "a rendered interface names known media");
    // The renderer's RGB index (n at the d line), the inside's per-channel absorption and its
    // scattering (cloudy ice: Cycles' Volume Scatter, density in 1/m as thaw's, HG anisotropy).
    const double n_in = inside->n_at(render::media::kFraunhoferD_nm);
    const double n_out = outside->n_at(render::media::kFraunhoferD_nm);
    const auto a = inside->absorption().srgb_per_m();
    media_pairs.push_back({{"name", name},
                           {"inside", face.inside},
                           {"outside", face.outside},
                           {"n_inside", n_in},
                           {"n_outside", n_out},
                           {"ior", n_in / n_out},
                           {"absorption_per_m", {a.r, a.g, a.b}},
                           {"roughness", face.roughness},
                           {"scattering_per_m", inside->scattering_per_m()},
                           {"scattering_g", inside->asymmetry()}});
  }
  data["interfaces"] = media_pairs;

  // The surfaces of every frame for any tool: each frame's file (relative to the run folder) and
  // where the renderer placed it (world = scale * file + translate, metres, y up).
  json listing;
  listing["format"] = "thaw-surfaces/1";
  listing["placement"] = "world_m = scale * file_m + translate_m, metres, y up";
  listing["fps"] = data["fps"];
  listing["frames"] = frames;
  listing["surfaces"] = json::array();
  for (const json& s : surfaces)
    listing["surfaces"].push_back({{"object", s["object"]},
                                   {"label", s["label"]},
                                   {"inside", s["inside"]},
                                   {"outside", s["outside"]},
                                   {"frames", s["frames"]}});
  write_file_atomic(handoff / "surfaces.json", listing.dump(1) + "\n");
  write_file_atomic(handoff / "camera.json",
                    camera_json(cam, sc.scene.image.width, sc.scene.image.height));
  required.push_back({"handoff/camera.json", in.stage});
  data["required"] = required;
  // A grid run with flow keeps the velocity in its fields (fields.pvd): the state shows it.
  const bool velocity =
      sc.simulation.grid != sim::GridGeometry::none && sc.simulation.natural_convection;
  write_paraview_state(handoff / "paraview_state.py", cam, sc.scene.image.width,
                       sc.scene.image.height, velocity);

  // The description goes into the script as a raw Python string; ' occurs in JSON only inside
  // strings, where \u0027 means the same.
  std::string text = data.dump(1);
  for (std::size_t p = 0; (p = text.find('\'', p)) != std::string::npos;)
    text.replace(p, 1, "\\u0027");
  std::string script(kBlenderSceneScript);
  const std::string marker = "THAW = {}  # @THAW_SCENE@ (thaw run puts the run's description here)";
  const std::size_t at = script.find(marker);
  THAW_CHECK(at != std::string::npos, "blender_scene.py has its THAW marker line");
  script.replace(at, marker.size(), "THAW = json.loads(r'''" + text + "''')");
  write_file_atomic(handoff / "blender_scene.py", script);
}

void write_run_handoff(const fs::path& run_dir, const RunScenario& sc,
                       const std::vector<sim::InterfaceRecord>& rows, const fs::path& mesh_dir,
                       const mesh::MeshManifest& meshes, const std::string& stage) {
  RunScenario framed = sc;
  framed.scene.camera = run_camera(sc, rows, meshes.geometry);
  const std::vector<WaterBudget> water =
      water_budget(rows, meshes.geometry, sc.simulation.materials.ice_density_kg_m3,
                   sc.simulation.materials.water_density_kg_m3);
  write_scene_handoff({run_dir, &framed, mesh_dir, &meshes, &water, stage});
}

}  // namespace thaw::pipeline
