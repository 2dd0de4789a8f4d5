#include "render/scene/scene.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>

#include "base/check.h"
#include "base/error.h"
#include "render/accel/ray_record.h"
#include "render/geometry/box.h"
#include "render/geometry/obj_loader.h"
#include "render/geometry/plane.h"
#include "render/geometry/shadow_cone.h"
#include "render/geometry/sphere.h"
#include "render/scene/scene_rules.h"

namespace thaw::render {

namespace {

Vec3 to_vec3(const Vec3d& v) {
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}
Rgb to_rgb(const RgbD& c) {
  return {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])};
}

Texture build_texture(const TextureDescription& t) {
  Texture tex;
  if (t.kind == TextureDescription::Kind::solid) {
    tex.kind = Texture::Kind::solid;
    tex.color0 = to_rgb(t.color);
  } else if (t.kind == TextureDescription::Kind::noise) {
    tex.kind = Texture::Kind::noise;
    tex.color0 = to_rgb(t.checker_colors[0]);
    tex.color1 = to_rgb(t.checker_colors[1]);
    tex.size = static_cast<float>(t.checker_size);
    tex.offset = to_vec3(t.checker_offset);
    tex.octaves = t.noise_octaves;
    tex.bump_m = static_cast<float>(t.bump_m);
    const bool known = noise_pattern_from_name(t.noise_pattern, tex.pattern);
    THAW_CHECK(known, "unknown noise pattern");
  } else {
    tex.kind = Texture::Kind::checker;
    tex.color0 = to_rgb(t.checker_colors[0]);
    tex.color1 = to_rgb(t.checker_colors[1]);
    tex.size = static_cast<float>(t.checker_size);
    tex.offset = to_vec3(t.checker_offset);
  }
  return tex;
}

Material build_material(const MaterialDescription& d) {
  Material m;
  m.texture = build_texture(d.texture);
  if (d.roughness > 0.0 &&
      (d.kind == MaterialDescription::Kind::metal || d.kind == MaterialDescription::Kind::phong)) {
    m.alpha = microfacet::alpha_from_roughness(static_cast<float>(d.roughness));
    m.albedo = std::make_shared<const microfacet::AlbedoTable>(m.alpha, 0.0f);
  }
  switch (d.kind) {
    case MaterialDescription::Kind::matte:
      m.kind = Material::Kind::matte;
      break;
    case MaterialDescription::Kind::metal:
      m.kind = Material::Kind::metal;
      break;
    case MaterialDescription::Kind::phong:
      m.kind = Material::Kind::phong;
      m.ka = static_cast<float>(d.ka);
      m.kd = static_cast<float>(d.kd);
      m.ks = static_cast<float>(d.ks);
      m.shininess = static_cast<float>(d.shininess);
      m.reflectance = static_cast<float>(d.reflectance);
      m.transmittance = static_cast<float>(d.transmittance);
      m.ior = static_cast<float>(d.ior);
      break;
    case MaterialDescription::Kind::emissive:
      m.kind = Material::Kind::emissive;
      m.emission = to_rgb(d.emission) * static_cast<float>(d.emission_intensity);
      break;
  }
  return m;
}

/// Whether an interface between media `a` and `b` changes nothing the renderer computes: the same
/// index at every rendered wavelength (1 nm steps over 380-780 nm; n_d alone in RGB scenes, which
/// use nothing else) to float precision, and no absorption on either side (RGB scenes absorb per
/// channel, spectral ones per wavelength).
bool index_matched(const media::Medium& a, const media::Medium& b, bool spectral) {
  if (a.absorbs() || b.absorbs()) return false;
  if (!spectral)
    return std::abs(a.n_at(media::kFraunhoferD_nm) - b.n_at(media::kFraunhoferD_nm)) <= 1e-7;
  for (int l = 380; l <= 780; ++l)
    if (std::abs(a.n_at(l) - b.n_at(l)) > 1e-7) return false;
  return true;
}

bool finite3f(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
/// placement_problem for a mesh once scaled and translated: its detail is its mean edge length,
/// its reach the largest coordinate [scene units]; the key is the transform that moved it there
/// ("translate", "scale"), or "file" for a mesh whose own coordinates are the problem.
std::optional<SceneProblem> mesh_placement_problem(const TriangleMesh& mesh, double scale,
                                                   const Vec3d& translate) {
  if (mesh.triangles.empty()) return std::nullopt;
  double edges = 0.0, reach = 0.0, own_reach = 0.0;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      edges += double(length(mesh.positions[t[(k + 1) % 3]] - mesh.positions[t[k]]));
  for (const Vec3& p : mesh.positions)
    for (int k = 0; k < 3; ++k) {
      own_reach = std::max(own_reach, std::abs(double(p[k])));
      reach = std::max(reach, std::abs(scale * p[k] + translate[k]));
    }
  const double detail = edges / (3.0 * double(mesh.triangles.size()));
  if (auto p = placement_problem(own_reach, detail)) return SceneProblem{"file", *p};
  if (auto p = placement_problem(reach, scale * detail))
    return SceneProblem{translate == Vec3d{0.0, 0.0, 0.0} ? "scale" : "translate", *p};
  return std::nullopt;
}

/// Signed distance [scene units] from `c` to the surface of a sphere, box or plane object
/// (negative inside a sphere or box; a plane's is unsigned); nullopt for meshes.
std::optional<double> signed_distance(const ObjectDescription& o, const Vec3d& c) {
  switch (o.shape) {
    case ObjectDescription::Shape::sphere: {
      const double dx = c[0] - o.center[0], dy = c[1] - o.center[1], dz = c[2] - o.center[2];
      return std::sqrt(dx * dx + dy * dy + dz * dz) - o.radius;
    }
    case ObjectDescription::Shape::box: {
      // Outside: distance to the nearest point; inside: minus the distance to the nearest face.
      double out2 = 0.0, in = -1e300;
      for (int k = 0; k < 3; ++k) {
        const double q = std::max(o.box_min[k] - c[k], c[k] - o.box_max[k]);
        if (q > 0.0) out2 += q * q;
        in = std::max(in, q);
      }
      return out2 > 0.0 ? std::sqrt(out2) : in;
    }
    case ObjectDescription::Shape::plane:
      return std::abs((c[0] - o.point[0]) * o.normal[0] + (c[1] - o.point[1]) * o.normal[1] +
                      (c[2] - o.point[2]) * o.normal[2]);
    case ObjectDescription::Shape::mesh:
      break;
  }
  return std::nullopt;
}

/// A light shut inside an opaque sphere or box that the camera is not in (a room or a dome the
/// camera shares is fine) lights nothing the camera can see; a sphere light whose surface cuts
/// an object's surface (sphere, box, plane) has no meaning. Both are the user's error. Meshes
/// are not checked (an open mesh has no inside).
void check_lights_outside_objects(const SceneDescription& desc) {
  for (std::size_t li = 0; li < desc.lights.size(); ++li) {
    const LightDescription& l = desc.lights[li];
    const std::string key = "lights[" + std::to_string(li) + "]";
    const double r = l.kind == LightDescription::Kind::sphere ? l.radius : 0.0;
    for (std::size_t oi = 0; oi < desc.objects.size(); ++oi) {
      const ObjectDescription& o = desc.objects[oi];
      const std::optional<double> sd = signed_distance(o, l.position);
      if (!sd) continue;
      const std::string name =
          "'" + (o.label.empty() ? "objects[" + std::to_string(oi) + "]" : o.label) + "'";
      const bool enclosing = o.shape != ObjectDescription::Shape::plane && !o.is_dielectric();
      if (enclosing && *sd < 0.0 && !(*signed_distance(o, desc.camera.position) < 0.0))
        throw UserError(desc.source_name, key + ".position",
                        "the light is inside opaque object " + name + " (and the camera is not)");
      if (r > 0.0 && std::abs(*sd) < r)
        throw UserError(
            desc.source_name, key + ".radius",
            "the sphere light (radius " + std::to_string(r) + ") intersects object " + name);
    }
  }
}

/// Largest |n_i - n_j| / |p_i - p_j| over the edges of the triangle (a, b, c) with vertex normals
/// (na, nb, nc): SurfaceInteraction::curvature of a triangle with shading normals.
float triangle_curvature(const Vec3& na, const Vec3& nb, const Vec3& nc, const Vec3& a,
                         const Vec3& b, const Vec3& c) {
  auto bend = [](const Vec3& n0, const Vec3& n1, const Vec3& p0, const Vec3& p1) {
    const float l = length(p1 - p0);
    return l > 0.0f ? length(n1 - n0) / l : 0.0f;
  };
  return std::max({bend(na, nb, a, b), bend(nb, nc, b, c), bend(nc, na, c, a)});
}

/// Unit geometric normal of a triangle primitive (+z for a degenerate one).
Vec3 triangle_normal(const Primitive& pr) {
  const Vec3 n = cross(pr.b - pr.a, pr.c - pr.a);
  const float len = length(n);
  return len > 0.0f ? n / len : Vec3{0, 0, 1};
}

/// Whether every vertex normal of `mesh` is its face's normal (either sign) to within 1e-7 in the
/// cosine (angle < 0.03 degrees), as a flat floor written with normals has them: interpolating
/// them gives the face normal to rounding, so the mesh is shaded flat and each hit skips the
/// interpolation and its square root (7 % of S4's CPU, whose floor is such a mesh).
bool normals_are_face_normals(const TriangleMesh& mesh) {
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Vec3 a = mesh.positions[tri[0]], b = mesh.positions[tri[1]], c = mesh.positions[tri[2]];
    const Vec3 face = cross(b - a, c - a);
    const float face_length = length(face);
    if (!(face_length > 0.0f)) return false;
    for (int corner = 0; corner < 3; ++corner) {
      const Vec3 n = mesh.normals[mesh.normal_indices[t][corner]];
      const float n_length = length(n);
      if (!(n_length > 0.0f) || std::abs(dot(n, face)) / (n_length * face_length) < 1.0f - 1e-7f)
        return false;
    }
  }
  return true;
}

/// The ray's ShearedRay, made on first use: a ray that reaches no triangle needs none.
class LazyShearedRay {
 public:
  explicit LazyShearedRay(const Ray& ray) : m_ray(ray) {}
  const ShearedRay& get() {
    if (!m_made) {
      m_sheared = ShearedRay(m_ray);
      m_made = true;
    }
    return m_sheared;
  }

 private:
  const Ray& m_ray;
  ShearedRay m_sheared;
  bool m_made = false;
};

}  // namespace

/// build_scene's steps, in order, each filling its part of the Scene (a friend): the checks of
/// the whole description, camera, lights, environment, media, materials, objects (shape by
/// shape), the visible sphere lights, the camera's medium, then the BVH and its leaf blocks.
class SceneBuilder {
 public:
  explicit SceneBuilder(const SceneDescription& desc) : m_desc(desc), m_src(desc.source_name) {}

  Scene build() {
    const auto start = std::chrono::steady_clock::now();
    if (const auto problem = find_scene_problem(m_desc))
      throw UserError(m_src, problem->key, problem->problem);
    m_s.m_settings = m_desc.image;
    m_s.m_caustics = m_desc.caustics;
    set_camera();
    add_lights();
    set_environment();
    add_media();
    add_materials();
    for (std::size_t i = 0; i < m_desc.objects.size(); ++i) add_object(i);
    check_lights_outside_objects(m_desc);
    add_visible_sphere_lights();
    choose_camera_medium();
    build_acceleration();
    m_s.m_stats.build_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return std::move(m_s);
  }

 private:
  /// The camera in single precision (find_scene_problem has checked it in double).
  void set_camera() {
    const CameraDescription& cam = m_desc.camera;
    const Vec3 pos = to_vec3(cam.position), at = to_vec3(cam.look_at), up = to_vec3(cam.up);
    if (!finite3f(pos) || !finite3f(at))
      throw UserError(m_src, "camera", "camera coordinates are beyond single precision");
    if (!(length(at - pos) > 0.0f))
      throw UserError(m_src, "camera.look_at", "must differ from the camera position");
    if (!(length(cross(normalize(at - pos), normalize(up))) > 1e-6f))
      throw UserError(m_src, "camera.up", "must not be parallel to the viewing direction");
    m_s.m_camera =
        Camera(pos, at, up, cam.vertical_fov_deg, m_desc.image.width, m_desc.image.height);
  }

  void add_lights() {
    for (const auto& l : m_desc.lights) {
      if (!finite3f(to_vec3(l.position)) || !std::isfinite(float(l.intensity)))
        throw UserError(m_src, "lights", "light position or intensity beyond single precision");
      const Rgb intensity = to_rgb(l.color) * static_cast<float>(l.intensity);
      const bool inverse_square = l.falloff == LightDescription::Falloff::inverse_square;
      if (l.kind == LightDescription::Kind::point) {
        m_s.m_lights.push_back({to_vec3(l.position), intensity, inverse_square});
        continue;
      }
      const auto radius = static_cast<float>(l.radius);
      m_s.m_sphere_lights.push_back({to_vec3(l.position), radius,
                                     sphere_light_radiance(intensity, radius), inverse_square,
                                     l.samples});
    }
    m_s.m_ambient = to_rgb(m_desc.ambient.color) * static_cast<float>(m_desc.ambient.intensity);
  }

  void set_environment() {
    m_s.m_background = to_rgb(m_desc.image.background);
    m_s.m_environment.background = m_s.m_background;
    if (m_desc.environment.kind == EnvironmentDescription::Kind::sky) {
      const EnvironmentDescription& e = m_desc.environment;
      const auto scale = static_cast<float>(e.intensity);
      m_s.m_environment.kind = Environment::Kind::sky;
      m_s.m_environment.zenith = to_rgb(e.zenith) * scale;
      m_s.m_environment.horizon = to_rgb(e.horizon) * scale;
      m_s.m_environment.ground = to_rgb(e.ground) * scale;
      m_s.m_environment.up = normalize(to_vec3(e.up));
      m_s.m_environment.exponent = static_cast<float>(e.exponent);
      for (const PanelDescription& pd : e.panels) {
        m_s.m_environment.panels.push_back(panel(pd));
        m_s.m_environment.panels.back().radiance *= scale;
      }
    } else if (m_desc.environment.kind == EnvironmentDescription::Kind::latlong) {
      const EnvironmentDescription& e = m_desc.environment;
      std::shared_ptr<const LatLongMap> map = e.map;
      if (!map) {
        const std::filesystem::path path = std::filesystem::path(e.file).is_absolute()
                                               ? std::filesystem::path(e.file)
                                               : m_desc.base_dir / e.file;
        std::string problem;
        auto loaded = load_latlong_map(path.string(), problem);
        if (!loaded)
          throw UserError(m_src, "environment.file", "'" + path.string() + "' " + problem);
        map = std::make_shared<const LatLongMap>(std::move(*loaded));
      }
      const double angle = e.rotation_deg * std::numbers::pi / 180.0;
      m_s.m_environment.kind = Environment::Kind::latlong;
      m_s.m_environment.map = std::move(map);
      m_s.m_environment.map_scale = static_cast<float>(e.intensity);
      m_s.m_environment.map_cos = static_cast<float>(std::cos(angle));
      m_s.m_environment.map_sin = static_cast<float>(std::sin(angle));
    }
    Environment& env = m_s.m_environment;
    env.light_surfaces = m_desc.environment.light_surfaces;
    env.occlusion_samples = m_desc.environment.occlusion_samples;
    env.haze_distance = static_cast<float>(m_desc.environment.haze_distance);
    if (env.light_surfaces)
      env.irradiance_sh = IrradianceSH::project([&env](const Vec3& d) { return env.radiance(d); });
  }

  /// A sky panel in the scene's frame: its centre, the horizontal `right` (perpendicular to the
  /// sky's up; any perpendicular at the zenith) and `top`, half-sizes and border in tangents.
  EnvironmentPanel panel(const PanelDescription& pd) const {
    constexpr double kDeg = std::numbers::pi / 180.0;
    EnvironmentPanel p;
    p.centre = normalize(to_vec3(pd.direction));
    Vec3 right = cross(p.centre, m_s.m_environment.up);
    if (length(right) < 1e-3f) right = cross(p.centre, Vec3{1.0f, 0.0f, 0.0f});
    p.right = normalize(right);
    p.top = cross(p.right, p.centre);
    p.half_width = static_cast<float>(std::tan(0.5 * pd.width_deg * kDeg));
    p.half_height = static_cast<float>(std::tan(0.5 * pd.height_deg * kDeg));
    p.edge = std::max(static_cast<float>(std::tan(pd.edge_deg * kDeg)), 1e-6f);
    p.radiance = to_rgb(pd.color) * static_cast<float>(pd.intensity);
    return p;
  }

  /// Vacuum and the described media; decides whether the render is spectral.
  void add_media() {
    m_s.m_media.push_back(
        {"vacuum", media::Medium("vacuum", media::IorModel::constant(1.0), media::Absorption())});
    bool wavelength_dependent = false;
    for (const auto& m : m_desc.media) {
      if (m_media.count(m.name))
        throw UserError(m_src, "media." + m.name, "medium defined twice (or redefines vacuum)");
      m_media[m.name] = static_cast<std::uint32_t>(m_s.m_media.size());
      // A full spec (Sellmeier, absorption, ...) is validated over 380-780 nm by render/media; a
      // bare constant index stays exactly the RGB path's number.
      media::Medium optics =
          m.spec ? media::build_medium(*m.spec)
                 : media::Medium(m.name, media::IorModel::constant(m.ior), media::Absorption());
      wavelength_dependent = wavelength_dependent || optics.is_dispersive() || optics.absorbs();
      m_s.m_media.push_back({m.name, std::move(optics)});
    }
    const ImageSettings& img = m_desc.image;
    m_s.m_spectral = img.spectral == ImageSettings::Spectral::on ||
                     (img.spectral == ImageSettings::Spectral::automatic && wavelength_dependent);
  }

  void add_materials() {
    for (const auto& m : m_desc.materials) {
      if (m_materials.count(m.name))
        throw UserError(m_src, "materials." + m.name, "material defined twice");
      m_materials[m.name] = static_cast<std::uint32_t>(m_s.m_materials.size());
      m_s.m_materials.push_back(build_material(m));
    }
  }

  /// The object's surface: the media on its two sides (a dielectric) or its material.
  SceneObject surface(const ObjectDescription& od, const std::string& label) {
    SceneObject obj;
    obj.label = label;
    obj.shape = od.shape;
    obj.dielectric = od.is_dielectric();
    if (!obj.dielectric) {
      auto m = m_materials.find(od.material);
      if (m == m_materials.end())
        throw UserError(m_src, label + ".material", "unknown material '" + od.material + "'");
      obj.material = m->second;
      return obj;
    }
    auto in = m_media.find(od.inside), out = m_media.find(od.outside);
    if (in == m_media.end())
      throw UserError(m_src, label + ".inside", "unknown medium '" + od.inside + "'");
    if (out == m_media.end())
      throw UserError(m_src, label + ".outside", "unknown medium '" + od.outside + "'");
    if (in->second == out->second)
      throw UserError(m_src, label, "inside and outside must be different media");
    obj.inside = in->second;
    obj.outside = out->second;
    obj.index_matched = index_matched(m_s.m_media[obj.inside].optics,
                                      m_s.m_media[obj.outside].optics, m_s.m_spectral);
    m_s.m_any_index_matched = m_s.m_any_index_matched || obj.index_matched;
    if (od.roughness > 0.0) {
      // The compensation's tables at the d line's indices (the lobe's albedo changes little
      // across the visible dispersion of ice or water).
      obj.alpha = microfacet::alpha_from_roughness(static_cast<float>(od.roughness));
      const auto eta =
          static_cast<float>(m_s.m_media[obj.inside].optics.n_at(media::kFraunhoferD_nm) /
                             m_s.m_media[obj.outside].optics.n_at(media::kFraunhoferD_nm));
      obj.albedo_entering = std::make_shared<const microfacet::AlbedoTable>(obj.alpha, eta);
      obj.albedo_leaving = std::make_shared<const microfacet::AlbedoTable>(obj.alpha, 1.0f / eta);
    }
    m_inside_media.insert(obj.inside);
    m_outside_media.insert(obj.outside);
    return obj;
  }

  void add_object(std::size_t index) {
    const ObjectDescription& od = m_desc.objects[index];
    const std::string label =
        od.label.empty() ? "objects[" + std::to_string(index) + "]" : od.label;
    SceneObject obj = surface(od, label);
    const auto id = static_cast<std::uint32_t>(m_s.m_objects.size());
    const std::size_t first_bound = m_bounds.size();
    switch (od.shape) {
      case ObjectDescription::Shape::sphere:
        add_sphere(to_vec3(od.center), static_cast<float>(od.radius), id);
        break;
      case ObjectDescription::Shape::box:
        add_box(od, id);
        break;
      case ObjectDescription::Shape::plane:
        add_plane(od, label, obj, id);
        break;
      case ObjectDescription::Shape::mesh:
        add_mesh(od, label, obj, id);
        break;
    }
    for (std::size_t b = first_bound; b < m_bounds.size(); ++b)
      if (!finite3f(m_bounds[b].lo) || !finite3f(m_bounds[b].hi))
        throw UserError(m_src, label,
                        "coordinates are too large (beyond single precision) or not finite");
    m_s.m_objects.push_back(std::move(obj));
  }

  void add_sphere(const Vec3& c, float r, std::uint32_t id) {
    Aabb b;
    b.extend(c - Vec3{r, r, r});
    b.extend(c + Vec3{r, r, r});
    m_bounds.push_back(b);
    m_prims.push_back({c, Vec3{r, 1.0f / r, 0}, Vec3{}, PrimitiveKind::sphere, id, 0});
    ++m_s.m_stats.spheres;
  }

  void add_box(const ObjectDescription& od, std::uint32_t id) {
    Aabb b;
    b.extend(to_vec3(od.box_min));
    b.extend(to_vec3(od.box_max));
    m_bounds.push_back(b);
    m_prims.push_back({b.lo, b.hi, Vec3{}, PrimitiveKind::box, id, 0});
    ++m_s.m_stats.boxes;
  }

  void add_plane(const ObjectDescription& od, const std::string& label, SceneObject& obj,
                 std::uint32_t id) {
    if (obj.dielectric)
      throw UserError(m_src, label, "a plane is not closed and cannot be a dielectric interface");
    obj.plane_point = to_vec3(od.point);
    obj.plane_normal = normalize(to_vec3(od.normal));
    m_s.m_planes.push_back(id);
    ++m_s.m_stats.planes;
  }

  /// The mesh in memory or from its file (each file read once), and the name errors give it.
  TriangleMesh load_mesh(const ObjectDescription& od, const std::string& label,
                         std::string& mesh_name) {
    if (od.mesh) {
      mesh_name = m_src;  // built in code: the label names it (not twice, as file and key)
      if (auto problem = validate_mesh(*od.mesh))
        throw UserError(m_src, label, "mesh: " + *problem);
      return *od.mesh;
    }
    if (od.mesh_file.empty())
      throw UserError(m_src, label, "mesh object needs a file or an in-memory mesh");
    const std::filesystem::path path =
        od.mesh_file.is_absolute() ? od.mesh_file : m_desc.base_dir / od.mesh_file;
    mesh_name = path.string();
    auto it = m_obj_cache.find(path);
    if (it == m_obj_cache.end()) it = m_obj_cache.emplace(path, load_obj(path)).first;
    return it->second;
  }

  void add_mesh(const ObjectDescription& od, const std::string& label, SceneObject& obj,
                std::uint32_t id) {
    std::string mesh_name;
    TriangleMesh mesh = load_mesh(od, label, mesh_name);
    // The OBJ file is to blame only for its own coordinates; a scale or translate that moves
    // the mesh too far is the scene file's (issue 27).
    if (const auto problem = mesh_placement_problem(mesh, od.scale, od.translate))
      throw UserError(problem->key == "file" ? mesh_name : m_src, label + "." + problem->key,
                      problem->key == "file" || mesh_name.empty()
                          ? problem->problem
                          : problem->problem + " (the mesh of " + mesh_name + ")");
    if (od.rotate_deg != Vec3d{0.0, 0.0, 0.0}) rotate_mesh(mesh, od.rotate_deg);
    if (od.scale != 1.0 || od.translate != Vec3d{0.0, 0.0, 0.0})
      transform_mesh(mesh, od.scale, od.translate);
    if (od.smooth_normals) compute_smooth_normals(mesh);
    if (obj.dielectric) {
      if (auto problem = closed_surface_problem(mesh))
        throw UserError(mesh_name, label,
                        "a dielectric mesh must be a closed surface: " + *problem);
      if (!(signed_volume(mesh) > 0.0))
        throw UserError(
            mesh_name, label,
            "a dielectric mesh must be oriented outward (its signed volume is not positive)");
    }
    if (mesh.has_normals() && !normals_are_face_normals(mesh)) {
      obj.normal_set = static_cast<int>(m_s.m_normal_sets.size());
      std::vector<float> curvature(mesh.triangles.size());
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        const auto& ni = mesh.normal_indices[t];
        curvature[t] = triangle_curvature(mesh.normals[ni[0]], mesh.normals[ni[1]],
                                          mesh.normals[ni[2]], mesh.positions[tri[0]],
                                          mesh.positions[tri[1]], mesh.positions[tri[2]]);
      }
      m_s.m_normal_sets.push_back(
          {std::move(mesh.normals), std::move(mesh.normal_indices), std::move(curvature)});
    }
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const auto& tri = mesh.triangles[t];
      const Vec3 a = mesh.positions[tri[0]], b = mesh.positions[tri[1]], c = mesh.positions[tri[2]];
      Aabb bb;
      bb.extend(a);
      bb.extend(b);
      bb.extend(c);
      m_bounds.push_back(bb);
      m_prims.push_back({a, b, c, PrimitiveKind::triangle, id, static_cast<std::uint32_t>(t)});
    }
    m_s.m_stats.triangles += mesh.triangles.size();
  }

  /// Sphere lights are visible: each is an opaque sphere of emissive material (radiance L) in
  /// the BVH, so camera and specular rays that meet it see L (the light itself, its highlight in
  /// the ice). Shadow rays towards a light stop just short of the point sampled on it.
  void add_visible_sphere_lights() {
    for (std::size_t i = 0; i < m_s.m_sphere_lights.size(); ++i) {
      SphereLight& l = m_s.m_sphere_lights[i];
      l.material = static_cast<std::uint32_t>(m_s.m_materials.size());
      Material m;
      m.kind = Material::Kind::emissive;
      m.emission = l.radiance;
      SceneObject obj;
      obj.label = "lights[" + std::to_string(i) + "]";
      obj.shape = ObjectDescription::Shape::sphere;
      obj.material = l.material;
      m_s.m_materials.push_back(m);
      const auto id = static_cast<std::uint32_t>(m_s.m_objects.size());
      m_s.m_objects.push_back(std::move(obj));
      add_sphere(l.center, l.radius, id);
    }
  }

  /// The camera's medium: given, or the one medium that is outside some interface but inside
  /// none.
  void choose_camera_medium() {
    if (!m_desc.camera.medium.empty()) {
      auto it = m_media.find(m_desc.camera.medium);
      if (it == m_media.end())
        throw UserError(m_src, "camera.medium", "unknown medium '" + m_desc.camera.medium + "'");
      m_s.m_camera_medium = it->second;
      return;
    }
    std::vector<std::uint32_t> outermost;
    for (auto m : m_outside_media)
      if (!m_inside_media.count(m)) outermost.push_back(m);
    if (outermost.size() == 1) {
      m_s.m_camera_medium = outermost[0];
    } else if (outermost.size() > 1) {
      std::string names;
      for (auto m : outermost) names += (names.empty() ? "" : ", ") + m_s.m_media[m].name;
      throw UserError(m_src, "camera.medium",
                      "the camera's medium is ambiguous (" + names + "): set camera.medium");
    }
  }

  /// The BVH over every primitive, the primitives in its order, triangle normals and the
  /// packed 4-triangle leaf blocks.
  void build_acceleration() {
    // Spheres, boxes and index-matched triangles are tested one by one, never in a 4-triangle
    // block (below), and the SAH must count them so.
    std::vector<std::uint8_t> tested_alone(m_prims.size());
    for (std::size_t i = 0; i < m_prims.size(); ++i)
      tested_alone[i] = m_prims[i].kind != PrimitiveKind::triangle ||
                        m_s.m_objects[m_prims[i].object].index_matched;
    m_s.m_bvh = Bvh(m_bounds, BvhBuildOptions{}, tested_alone);
    m_s.m_primitives.resize(m_prims.size());
    for (std::size_t i = 0; i < m_prims.size(); ++i)
      m_s.m_primitives[i] = m_prims[m_s.m_bvh.order()[i]];
    m_s.m_triangle_normals.assign(m_s.m_primitives.size(), Vec3{0, 0, 0});
    for (std::size_t i = 0; i < m_s.m_primitives.size(); ++i) {
      const Primitive& pr = m_s.m_primitives[i];
      if (pr.kind == PrimitiveKind::triangle) m_s.m_triangle_normals[i] = triangle_normal(pr);
    }
    m_s.m_leaf_block.assign(m_s.m_primitives.size(), Scene::kNoBlock);
    for (const Bvh4Node& n : m_s.m_bvh.wide_nodes()) {
      for (int i = 0; i < 4; ++i) {
        const std::uint32_t first = n.child[i], count = n.count[i];
        if (count == 0 || count > 4) continue;
        // Index-matched triangles stay out of the blocks: occluded() must be able to skip them.
        bool all_triangles = true;
        for (std::uint32_t k = first; k < first + count; ++k)
          all_triangles = all_triangles && m_s.m_primitives[k].kind == PrimitiveKind::triangle &&
                          !m_s.m_objects[m_s.m_primitives[k].object].index_matched;
        if (!all_triangles) continue;
        Triangle4 block{};
        for (std::uint32_t lane = 0; lane < 4; ++lane) {
          const std::uint32_t k = first + (lane < count ? lane : 0);  // unused lanes repeat lane 0
          const Primitive& p = m_s.m_primitives[k];
          block.set(static_cast<int>(lane), p.a, p.b, p.c, k);
        }
        m_s.m_leaf_block[first] = static_cast<std::uint32_t>(m_s.m_leaf_triangles.size());
        m_s.m_leaf_triangles.push_back(block);
      }
    }
    m_s.m_stats.bvh_nodes = m_s.m_bvh.nodes().size();
    m_s.m_stats.bvh_depth = m_s.m_bvh.depth();
  }

  const SceneDescription& m_desc;
  const std::string& m_src;
  Scene m_s;
  std::map<std::string, std::uint32_t> m_media{{"vacuum", 0}}, m_materials;
  std::vector<Aabb> m_bounds;
  std::vector<Primitive> m_prims;
  std::map<std::filesystem::path, TriangleMesh> m_obj_cache;
  std::set<std::uint32_t> m_inside_media, m_outside_media;
};

namespace {
/// The shadow cone's test of an 8-wide node's children, for Bvh::any_leaf_wide8: SSE halves and
/// AVX2 (the same bits).
struct ConeBoxes8 {
  const ShadowCone& cone;
  unsigned operator()(const float (&planes)[6][8]) const { return cone.may_touch_boxes8(planes); }
};
struct ConeBoxes8Avx2 {
  const ShadowCone& cone;
  THAW_TARGET_AVX2 unsigned operator()(const float (&planes)[6][8]) const {
#if THAW_AVX2_DISPATCH
    return cone.may_touch_boxes8_avx2(planes);
#else
    return cone.may_touch_boxes8(planes);
#endif
  }
};
}  // namespace

Scene build_scene(const SceneDescription& desc) {
  return SceneBuilder(desc).build();
}

bool Scene::intersect(const Ray& ray, Hit& hit) const {
  record_ray(RayQuery::closest, ray);
  float t_max = ray.t_max;
  bool found = false;
  // Planes first: their hit bounds the tree's traversal (the floor culls every node beneath it,
  // e.g. the puddle mesh's part sunk below the floor). A primitive at exactly the plane's t still
  // wins, as when the planes were tested last (the traversal keeps hits with t < its bound).
  for (std::uint32_t k = 0; k < m_planes.size(); ++k) {
    const SceneObject& o = m_objects[m_planes[k]];
    float t;
    if (intersect_plane(ray, o.plane_point, o.plane_normal, t_max, t)) {
      t_max = t;
      hit.t = t;
      hit.prim = kPlaneBit | k;
      found = true;
    }
  }
  if (!m_bvh.empty()) {
    if (found) t_max = std::nextafter(t_max, std::numeric_limits<float>::infinity());
    const Bvh::RayData rd(ray);
    // The shear transform (3 divisions) serves triangles only: made at the first triangle leaf
    // the ray reaches (many rays reach none, e.g. those leaving a floor upwards).
    LazyShearedRay sr(ray);
    const Primitive* prims = m_primitives.data();
    found |= m_bvh.intersect(rd, t_max, [&](std::uint32_t first, std::uint32_t count, float& tm) {
      const std::uint32_t block = m_leaf_block[first];
      if (block != kNoBlock) {
        TriangleHit th;
        int lane;
        if (!intersect_triangle4(sr.get(), m_leaf_triangles[block], tm, th, lane)) return false;
        tm = th.t;
        hit.t = th.t;
        hit.b1 = th.b1;
        hit.b2 = th.b2;
        hit.prim = m_leaf_triangles[block].prim[lane];
        return true;
      }
      bool any = false;
      for (std::uint32_t i = first; i < first + count; ++i) {
        const Primitive& p = prims[i];
        if (p.kind == PrimitiveKind::triangle) [[likely]] {
          TriangleHit th;
          if (intersect_triangle(sr.get(), p.a, p.b, p.c, tm, th)) {
            tm = th.t;
            hit.t = th.t;
            hit.b1 = th.b1;
            hit.b2 = th.b2;
            hit.prim = i;
            any = true;
          }
        } else if (p.kind == PrimitiveKind::sphere) {
          float t;
          if (intersect_sphere(ray, p.a, p.b.x, tm, t)) {
            tm = t;
            hit.t = t;
            hit.prim = i;
            any = true;
          }
        } else {
          float t;
          int axis;
          bool high;
          if (intersect_box(ray, p.a, p.b, tm, t, axis, high)) {
            tm = t;
            hit.t = t;
            hit.prim = i;
            hit.aux = static_cast<std::uint32_t>(2 * axis + (high ? 1 : 0));
            any = true;
          }
        }
      }
      return any;
    });
  }
  return found;
}

bool Scene::light_unoccluded(const Vec3& origin, std::size_t light) const {
  const SphereLight& l = m_sphere_lights[light];
  const Vec3 to_light = l.center - origin;
  const float d = length(to_light);
  if (!(d > l.radius)) return false;
  // Slack for the float rounding of the tests: 1e-4 of the cone's length (0.1 mm at 1 m), far
  // above float's 6e-8 relative error and far below any gap that matters.
  const float slack = 1e-4f * (d + l.radius);
  for (const std::uint32_t k : m_planes) {
    // intersect_plane's t = num / dot(direction, n), num the same for all rays from `origin`:
    // num = 0 never gives t > 0; otherwise only rays heading to the plane's side opposite to the
    // origin can meet it, which end at the ball first if the ball lies wholly on the origin's side.
    const SceneObject& o = m_objects[k];
    const float num = dot(o.plane_point - origin, o.plane_normal);
    const float s_l = dot(l.center - o.plane_point, o.plane_normal);
    const bool clear = num == 0.0f || (num < 0.0f && s_l > l.radius + slack) ||
                       (num > 0.0f && s_l < -(l.radius + slack));
    if (!clear) return false;
  }
  const ShadowCone cone(origin, l.center, l.radius, slack);
  const Primitive* prims = m_primitives.data();
  const auto leaf = [&](std::uint32_t first, std::uint32_t count) {
    for (std::uint32_t i = first; i < first + count; ++i) {
      const Primitive& p = prims[i];
      // The light's own visible sphere: the rays stop short of it.
      if (p.kind == PrimitiveKind::sphere && p.a == l.center && p.b.x == l.radius) continue;
      const bool touches =
          p.kind == PrimitiveKind::sphere
              ? cone.may_touch_sphere(p.a, p.b.x)
              : (p.kind == PrimitiveKind::box
                     ? cone.may_touch_box(p.a, p.b)
                     : cone.may_touch_box(min(min(p.a, p.b), p.c), max(max(p.a, p.b), p.c)));
      if (touches) return true;
    }
    return false;
  };
  if (m_bvh.wide8_nodes().empty())
    return !m_bvh.any_leaf_wide(
        [&](const float(&planes)[6][4]) { return cone.may_touch_boxes4(planes); }, leaf);
  return !m_bvh.any_leaf_wide8(ConeBoxes8{cone}, ConeBoxes8Avx2{cone}, leaf);
}

bool Scene::occluded(const Ray& ray) const {
  record_ray(RayQuery::any, ray);
  for (std::uint32_t k = 0; k < m_planes.size(); ++k) {
    const SceneObject& o = m_objects[m_planes[k]];
    float t;
    if (intersect_plane(ray, o.plane_point, o.plane_normal, ray.t_max, t)) return true;
  }
  if (m_bvh.empty()) return false;
  const Bvh::RayData rd(ray);
  LazyShearedRay sr(ray);
  const Primitive* prims = m_primitives.data();
  const bool skip_matched = m_any_index_matched;
  return m_bvh.occluded(rd, ray.t_max, [&](std::uint32_t first, std::uint32_t count, float tm) {
    const std::uint32_t block = m_leaf_block[first];
    if (block != kNoBlock) {
      TriangleHit th;
      int lane;
      return intersect_triangle4(sr.get(), m_leaf_triangles[block], tm, th, lane, true);
    }
    for (std::uint32_t i = first; i < first + count; ++i) {
      const Primitive& p = prims[i];
      if (skip_matched && m_objects[p.object].index_matched)
        continue;  // invisible: lets light through
      float t;
      if (p.kind == PrimitiveKind::triangle) [[likely]] {
        TriangleHit th;
        if (intersect_triangle(sr.get(), p.a, p.b, p.c, tm, th)) return true;
      } else if (p.kind == PrimitiveKind::sphere) {
        if (intersect_sphere(ray, p.a, p.b.x, tm, t)) return true;
      } else {
        int axis;
        bool high;
        if (intersect_box(ray, p.a, p.b, tm, t, axis, high)) return true;
      }
    }
    return false;
  });
}

SurfaceInteraction Scene::interaction(const Ray& ray, const Hit& hit) const {
  SurfaceInteraction si;
  if (hit.prim & kPlaneBit) {
    const std::uint32_t oi = m_planes[hit.prim & ~kPlaneBit];
    const SceneObject& o = m_objects[oi];
    Vec3 p = ray.at(hit.t);
    // Project back onto the plane; the remaining error is a few ulps of the coordinates involved.
    p = p - o.plane_normal * dot(p - o.plane_point, o.plane_normal);
    si.p = p;
    si.p_error = (abs(p) + abs(o.plane_point)) * gamma_bound(6);
    si.ng = si.ns = o.plane_normal;
    si.object = oi;
    return si;
  }
  const Primitive& pr = m_primitives[hit.prim];
  si.object = pr.object;
  switch (pr.kind) {
    case PrimitiveKind::triangle: {
      const float b0 = 1.0f - hit.b1 - hit.b2;
      // Barycentric reconstruction and its error bound (pbrt-v4
      // Triangle::InteractionFromIntersection).
      si.p = pr.a * b0 + pr.b * hit.b1 + pr.c * hit.b2;
      si.p_error = (abs(pr.a * b0) + abs(pr.b * hit.b1) + abs(pr.c * hit.b2)) * gamma_bound(7);
      si.ng = si.ns = m_triangle_normals[hit.prim];
      const int set = m_objects[pr.object].normal_set;
      if (set >= 0) {
        const NormalSet& ns = m_normal_sets[static_cast<std::size_t>(set)];
        const auto& idx = ns.indices[pr.index];
        const Vec3 sn =
            ns.normals[idx[0]] * b0 + ns.normals[idx[1]] * hit.b1 + ns.normals[idx[2]] * hit.b2;
        const float sl = length(sn);
        if (sl > 0.0f) si.ns = face_forward(sn / sl, si.ng);
        si.curvature = ns.curvature[pr.index];
      }
      break;
    }
    case PrimitiveKind::sphere: {
      const Vec3 c = pr.a;
      const float r = pr.b.x, inv_r = pr.b.y;
      Vec3 d = ray.at(hit.t) - c;
      const float dl = length(d);
      d = dl > 0.0f ? d * (r / dl) : Vec3{0, r, 0};
      si.p = c + d;  // reprojected onto the sphere (pbrt-v4 Sphere::Intersect)
      si.p_error = (abs(d) + abs(c)) * gamma_bound(6);
      si.ng = si.ns = d * inv_r;  // = d / r (Vec3's operator/ multiplies by 1 / r)
      si.curvature = inv_r;
      break;
    }
    case PrimitiveKind::box: {
      const int axis = static_cast<int>(hit.aux / 2);
      const bool high = (hit.aux & 1u) != 0;
      Vec3 p = ray.at(hit.t);
      p[axis] = high ? pr.b[axis] : pr.a[axis];  // exactly on the face
      si.p = p;
      si.p_error = abs(p) * gamma_bound(3);
      Vec3 n{0, 0, 0};
      n[axis] = high ? 1.0f : -1.0f;
      si.ng = si.ns = n;
      break;
    }
  }
  return si;
}

}  // namespace thaw::render
