#include "render/format/scene_parser.h"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "base/error.h"
#include "base/format/key_table_toml.h"
#include "base/format/toml_table.h"
#include "base/text_file.h"
#include "render/format/medium_library.h"
#include "render/format/medium_parser.h"
#include "render/light/latlong_map.h"
#include "render/material/texture.h"
#include "render/scene/camera_keys.h"
#include "render/scene/caustic_keys.h"
#include "render/scene/environment_keys.h"
#include "render/scene/image_keys.h"
#include "render/scene/light_keys.h"

namespace thaw::render {

namespace {

RgbD color3(const TomlTable& t, const std::string& key, const RgbD& fallback) {
  const RgbD c = t.get_vec3(key, fallback);
  for (double v : c)
    if (v < 0.0) t.fail(key, "colour components must not be negative");
  return c;
}

/// `value` unless `rule` finds a problem with it, which is then the file's error at `key`.
template <typename T, typename Rule>
T checked(const TomlTable& t, const std::string& key, T value, Rule rule) {
  if (const std::optional<std::string> problem = rule(value)) t.fail(key, *problem);
  return value;
}

/// An integer key checked by `rule` on its full 64-bit value, before it is narrowed to int.
template <typename Rule>
int int_key(const TomlTable& t, const std::string& key, int fallback, Rule rule) {
  return static_cast<int>(checked<long long>(t, key, t.get_int(key, fallback), rule));
}

/// [image]: every key by its row; every limit is a rule of render/scene/scene_rules.h.
ImageSettings parse_image(const TomlTable& img, ImageSettings image) {
  read_keys(img, image_keys(), image);
  if (const auto problem = image_pixels_problem(image.width, image.height))
    img.fail("height", *problem);
  return image;
}

TextureDescription parse_texture(const TomlTable& m) {
  TextureDescription tex;
  if (m.has("checker")) {
    if (m.has("color")) m.fail("color", "give either color or checker, not both");
    const TomlTable c = m.table("checker");
    tex.kind = TextureDescription::Kind::checker;
    const auto colors = c.get_vec3s("colors");
    if (colors.size() != 2) c.fail("colors", "expected two colours [[r, g, b], [r, g, b]]");
    for (const auto& col : colors)
      for (double v : col)
        if (v < 0.0) c.fail("colors", "colour components must not be negative");
    tex.checker_colors = {colors[0], colors[1]};
    tex.checker_size = c.require_positive("size", c.get_double("size"));
    tex.checker_offset = c.get_vec3("offset", {0.0, 0.0, 0.0});
  } else if (m.has("noise")) {
    if (m.has("color")) m.fail("color", "give either color or noise, not both");
    const TomlTable c = m.table("noise");
    tex.kind = TextureDescription::Kind::noise;
    tex.noise_pattern = c.get_string("pattern");
    Texture::Pattern pattern;
    if (!noise_pattern_from_name(tex.noise_pattern, pattern))
      c.fail("pattern", "expected \"perlin\", \"worley\", \"wood\" or \"slate\"");
    const auto colors = c.get_vec3s("colors");
    if (colors.size() != 2) c.fail("colors", "expected two colours [[r, g, b], [r, g, b]]");
    for (const auto& col : colors)
      for (double v : col)
        if (!(v >= 0.0) || !std::isfinite(v))
          c.fail("colors", "colour components must be finite and not negative");
    tex.checker_colors = {colors[0], colors[1]};
    tex.checker_size = c.require_positive("scale", c.get_double("scale"));
    tex.checker_offset = c.get_vec3("offset", {0.0, 0.0, 0.0});
    const std::int64_t octaves = c.get_int("octaves", 5);
    if (octaves < 1 || octaves > 12) c.fail("octaves", "must be an integer from 1 to 12");
    tex.noise_octaves = int(octaves);
    tex.bump_m = c.get_double("bump_m", 0.0);
    if (!(tex.bump_m >= 0.0 && tex.bump_m <= 0.1)) c.fail("bump_m", "must be from 0 to 0.1 [m]");
  } else {
    tex.kind = TextureDescription::Kind::solid;
    tex.color = color3(m, "color", {0.8, 0.8, 0.8});
  }
  return tex;
}

MaterialDescription parse_material(const std::string& name, const TomlTable& m) {
  MaterialDescription mat;
  mat.name = name;
  const std::string kind = m.get_string("kind");
  if (kind == "matte") {
    mat.kind = MaterialDescription::Kind::matte;
    mat.texture = parse_texture(m);
  } else if (kind == "metal") {
    mat.kind = MaterialDescription::Kind::metal;
    mat.texture = parse_texture(m);
    mat.roughness = checked(m, "roughness", m.get_double("roughness", 0.0), roughness_problem);
  } else if (kind == "phong") {
    mat.kind = MaterialDescription::Kind::phong;
    mat.texture = parse_texture(m);
    mat.ka = m.require_non_negative("ka", m.get_double("ka", 0.1));
    mat.kd = m.require_non_negative("kd", m.get_double("kd", 0.9));
    mat.ks = m.require_non_negative("ks", m.get_double("ks", 0.0));
    mat.shininess = m.require_positive("shininess", m.get_double("shininess", 32.0));
    mat.reflectance = m.require_non_negative("reflectance", m.get_double("reflectance", 0.0));
    mat.transmittance = m.require_non_negative("transmittance", m.get_double("transmittance", 0.0));
    mat.ior = m.require_positive("ior", m.get_double("ior", 1.0));
    mat.roughness = checked(m, "roughness", m.get_double("roughness", 0.0), roughness_problem);
  } else if (kind == "emissive") {
    mat.kind = MaterialDescription::Kind::emissive;
    mat.emission = color3(m, "color", {1.0, 1.0, 1.0});
    mat.emission_intensity = m.require_non_negative("intensity", m.get_double("intensity", 1.0));
  } else {
    m.fail("kind",
           "unknown material kind '" + kind + "' (expected matte, metal, phong or emissive)");
  }
  return mat;
}

/// [environment]: constant, sky or latlong; the keys of the other kinds stay unread (unknown-key
/// errors). A lat-long map's file is read here, once (a film's frames share it).
void parse_environment(const TomlTable& env, SceneDescription& s) {
  EnvironmentDescription& e = s.environment;
  read_keys(env, environment_keys(), e);
  if (e.kind == EnvironmentDescription::Kind::sky) {
    for (const TomlTable& t : env.array_of_tables("panels")) {
      PanelDescription panel;
      panel.direction = unit_vector(t, "direction");
      panel.width_deg = checked(t, "width_deg", t.get_double("width_deg"), panel_size_problem);
      panel.height_deg = checked(t, "height_deg", t.get_double("height_deg"), panel_size_problem);
      panel.edge_deg =
          checked(t, "edge_deg", t.get_double("edge_deg", panel.edge_deg), panel_edge_problem);
      panel.color = color3(t, "color", panel.color);
      panel.intensity = checked(t, "intensity", t.get_double("intensity", panel.intensity),
                                environment_intensity_problem);
      e.panels.push_back(panel);
    }
  } else if (e.kind == EnvironmentDescription::Kind::latlong) {
    const std::filesystem::path path = std::filesystem::path(e.file).is_absolute()
                                           ? std::filesystem::path(e.file)
                                           : s.base_dir / e.file;
    std::string problem;
    auto map = load_latlong_map(path.string(), problem);
    if (!map) env.fail("file", "'" + path.string() + "' " + problem);
    e.map = std::make_shared<const LatLongMap>(std::move(*map));
  }
}

/// [caustics]: every key by its row (render/scene/caustic_keys.h).
CausticSettings parse_caustics(const TomlTable& c) {
  CausticSettings caustics;
  read_keys(c, caustic_keys(), caustics);
  return caustics;
}

/// [camera]: every key by its row (render/scene/camera_keys.h), then the rules between them.
CameraDescription parse_camera(const TomlTable& cam) {
  CameraDescription camera;
  read_keys(cam, camera_keys(), camera);
  if (const auto problem = camera_problem(camera)) cam.fail(problem->key, problem->problem);
  return camera;
}

/// One [[lights]] entry: every key by its row (render/scene/light_keys.h).
LightDescription parse_light(const TomlTable& l) {
  LightDescription light;
  read_keys(l, light_keys(), light);
  return light;
}

/// [media.NAME] tables into `s.media`; returns every medium name an object may use.
std::set<std::string> parse_media(const TomlTable& root, SceneDescription& s) {
  std::set<std::string> media{"vacuum"};
  const auto med = root.optional_table("media");
  if (!med) return media;
  for (const std::string& name : med->keys()) {
    const TomlTable m = med->table(name);
    MediumDescription md;
    md.name = name;
    if (m.has("ior")) md.ior = checked(m, "ior", m.get_double("ior"), ior_problem);
    if (name == "vacuum")
      m.fail(m.has("ior") ? "ior" : "", "'vacuum' is predefined (n = 1) and cannot be redefined");
    // Everything else a medium may say (preset, sellmeier, ..., absorption): render/media.
    md.spec = media::resolve_preset(media::parse_medium_spec(m, name));
    media.insert(name);
    s.media.push_back(md);
  }
  return media;
}

/// [materials.NAME] tables into `s.materials`; returns their names.
std::set<std::string> parse_materials(const TomlTable& root, SceneDescription& s) {
  std::set<std::string> materials;
  if (auto mats = root.optional_table("materials")) {
    for (const std::string& name : mats->keys()) {
      s.materials.push_back(parse_material(name, mats->table(name)));
      materials.insert(name);
    }
  }
  return materials;
}

/// An object's `shape` and the keys that place it.
void parse_shape(const TomlTable& o, ObjectDescription& obj) {
  const std::string shape = o.get_string("shape");
  if (shape == "sphere") {
    obj.shape = ObjectDescription::Shape::sphere;
    obj.center = o.get_vec3("center");
    obj.radius = o.get_double("radius");
  } else if (shape == "box") {
    obj.shape = ObjectDescription::Shape::box;
    obj.box_min = o.get_vec3("min");
    obj.box_max = o.get_vec3("max");
  } else if (shape == "plane") {
    obj.shape = ObjectDescription::Shape::plane;
    obj.point = o.get_vec3("point");
    obj.normal = unit_vector(o, "normal");
  } else if (shape == "mesh") {
    obj.shape = ObjectDescription::Shape::mesh;
    const std::string file = o.get_string("file");
    if (file.empty()) o.fail("file", "must name an OBJ file");
    obj.mesh_file = file;
    obj.scale = o.get_double("scale", 1.0);
    obj.rotate_deg = o.get_vec3("rotate_deg", {0.0, 0.0, 0.0});
    obj.translate = o.get_vec3("translate", {0.0, 0.0, 0.0});
    obj.smooth_normals = o.get_bool("smooth_normals", false);
  } else {
    o.fail("shape", "unknown shape '" + shape + "' (expected mesh, sphere, box or plane)");
  }
  if (const auto problem = object_problem(obj)) o.fail(problem->key, problem->problem);
}

/// An object is opaque (`material`) or a dielectric interface (`inside`, `outside`).
void parse_surface(const TomlTable& o, const std::set<std::string>& materials,
                   const std::set<std::string>& media, ObjectDescription& obj) {
  const bool has_material = o.has("material");
  const bool has_media = o.has("inside") || o.has("outside");
  if (has_material && has_media)
    o.fail("material",
           "an object is either opaque (material) or a dielectric interface (inside, outside), "
           "not both");
  if (has_material) {
    obj.material = o.get_string("material");
    if (!materials.count(obj.material))
      o.fail("material", "unknown material '" + obj.material + "'");
  } else if (has_media) {
    obj.inside = o.get_string("inside");
    obj.outside = o.get_string("outside");
    if (!media.count(obj.inside)) o.fail("inside", "unknown medium '" + obj.inside + "'");
    if (!media.count(obj.outside)) o.fail("outside", "unknown medium '" + obj.outside + "'");
    if (obj.inside == obj.outside) o.fail("outside", "inside and outside must be different media");
    obj.roughness = checked(o, "roughness", o.get_double("roughness", 0.0), roughness_problem);
    if (obj.shape == ObjectDescription::Shape::plane)
      o.fail("inside",
             "a plane is not closed and cannot be a dielectric interface; give it a material");
  } else {
    o.fail("shape", "object needs either material = \"...\" or inside/outside media");
  }
}

ObjectDescription parse_object(const TomlTable& o, const std::set<std::string>& materials,
                               const std::set<std::string>& media) {
  ObjectDescription obj;
  obj.label = o.has("name") ? o.get_string("name") : o.path();
  parse_shape(o, obj);
  parse_surface(o, materials, media, obj);
  return obj;
}

}  // namespace

SceneDescription parse_scene_string(const std::string& text, const std::string& source_name,
                                    const std::filesystem::path& base_dir) {
  const TomlTable root = TomlTable::parse_string(text, source_name);
  SceneDescription s = parse_scene_table(root, base_dir);
  root.check_no_unknown_keys();
  return s;
}

SceneDescription parse_scene_table(const TomlTable& root, const std::filesystem::path& base_dir,
                                   bool camera_optional) {
  SceneDescription s;
  s.source_name = root.source_name();
  s.base_dir = base_dir;
  if (auto img = root.optional_table("image")) s.image = parse_image(*img, s.image);
  if (auto c = root.optional_table("caustics")) s.caustics = parse_caustics(*c);
  if (auto env = root.optional_table("environment")) parse_environment(*env, s);
  if (auto cam = root.optional_table("camera"))
    s.camera = parse_camera(*cam);
  else if (!camera_optional)
    root.fail("camera", "required table [camera] is missing");
  if (auto amb = root.optional_table("ambient")) {
    s.ambient.color = color3(*amb, "color", s.ambient.color);
    s.ambient.intensity = amb->require_non_negative("intensity", amb->get_double("intensity", 0.0));
  }
  for (const TomlTable& l : root.array_of_tables("lights")) s.lights.push_back(parse_light(l));
  const std::set<std::string> media = parse_media(root, s);
  const std::set<std::string> materials = parse_materials(root, s);
  if (!s.camera.medium.empty() && !media.count(s.camera.medium))
    root.table("camera").fail("medium", "unknown medium '" + s.camera.medium + "'");
  for (const TomlTable& o : root.array_of_tables("objects"))
    s.objects.push_back(parse_object(o, materials, media));
  return s;
}

SceneDescription parse_scene_file(const std::filesystem::path& path) {
  return parse_scene_string(read_text_file(path, "a TOML file", kMaxTomlFileBytes), path.string(),
                            path.parent_path());
}

}  // namespace thaw::render
