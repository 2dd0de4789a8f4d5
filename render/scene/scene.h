#pragma once
// A renderable scene: primitives (triangles, spheres, boxes) in one BVH, infinite planes beside
// it, opaque materials, media with their IOR models, dielectric interfaces naming the medium
// inside and outside, lights and camera. Built once from a SceneDescription by build_scene(),
// which loads and checks meshes (a dielectric mesh must be closed and outward oriented);
// immutable and shared by all render threads afterwards. Knows nothing about TOML or images.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/accel/bvh.h"
#include "render/geometry/triangle4.h"
#include "render/light/environment.h"
#include "render/light/sphere_light.h"
#include "render/material/material.h"
#include "render/math/color.h"
#include "render/media/medium.h"
#include "render/scene/camera.h"
#include "render/scene/scene_description.h"

namespace thaw::render {

enum class PrimitiveKind : std::uint32_t { triangle = 0, sphere = 1, box = 2 };

/// One BVH primitive, stored in leaf order. Triangle: vertices a, b, c. Sphere: centre a,
/// radius b.x and 1 / radius in b.y (the hit's normal and curvature, no division per hit). Box:
/// corners a (min) and b (max).
struct Primitive {
  Vec3 a, b, c;
  PrimitiveKind kind;
  /// index into Scene::objects()
  std::uint32_t object;
  /// triangle index within its mesh (for shading normals)
  std::uint32_t index;
};
static_assert(sizeof(Primitive) == 48);

struct Medium {
  std::string name;
  /// n(lambda) and Beer-Lambert absorption (render/media); the RGB integrator uses n at the
  /// helium d line (media::kFraunhoferD_nm), which is the number itself for a constant index
  media::Medium optics;
};

struct SceneObject {
  std::string label;
  ObjectDescription::Shape shape = ObjectDescription::Shape::sphere;
  bool dielectric = false;
  /// opaque objects: index into Scene::materials()
  std::uint32_t material = 0;
  /// dielectric interfaces: indices into Scene::media()
  std::uint32_t inside = 0, outside = 0;
  /// dielectric whose inside and outside have the same index at every rendered wavelength (n_d
  /// only in RGB scenes) and do not absorb (spectral scenes): invisible, so shadow rays pass
  /// through it (occluded()) and photons crossing only such interfaces are direct light
  bool index_matched = false;
  /// rough dielectric interfaces: GGX alpha (0 = smooth) and the directional albedo of the lobe
  /// seen from outside (eta = n_inside / n_outside at the d line) and from inside, for the
  /// multiple-scattering compensation (render/material/microfacet.h)
  float alpha = 0.0f;
  std::shared_ptr<const microfacet::AlbedoTable> albedo_entering, albedo_leaving;
  /// meshes with shading normals: index into the scene's normal sets, else -1
  int normal_set = -1;
  // plane
  Vec3 plane_point, plane_normal;
};

struct PointLight {
  Vec3 position;
  /// colour * intensity
  Rgb radiance;
  bool inverse_square = false;
};

/// Result of a ray query: distance and enough to reconstruct the surface point.
struct Hit {
  float t = 0;
  /// barycentrics of the 2nd and 3rd vertex (triangles)
  float b1 = 0, b2 = 0;
  /// primitive index (leaf order) or kPlaneBit | plane index
  std::uint32_t prim = 0;
  /// boxes: 2 * axis + (1 if the face at max)
  std::uint32_t aux = 0;
};
inline constexpr std::uint32_t kPlaneBit = 0x80000000u;

/// The surface at a hit: point with its rounding-error bound, unit geometric normal (outward for
/// closed surfaces, as given for planes) and unit shading normal (same side as the geometric one).
struct SurfaceInteraction {
  Vec3 p, p_error, ng, ns;
  std::uint32_t object = 0;
  /// estimate of the surface's largest curvature [1/scene units]: 1/r on spheres; on meshes with
  /// shading normals the largest |n_i - n_j| / |p_i - p_j| over the triangle's edges; 0 on
  /// planes, boxes and flat-shaded triangles (ray cones, render/integrator/whitted_shading.h)
  float curvature = 0;
};

struct SceneStatistics {
  std::size_t triangles = 0, spheres = 0, boxes = 0, planes = 0, bvh_nodes = 0;
  int bvh_depth = 0;
  double build_seconds = 0;
};

class Scene {
 public:
  const ImageSettings& settings() const { return m_settings; }
  const CausticSettings& caustics() const { return m_caustics; }
  const Camera& camera() const { return m_camera; }
  const std::vector<PointLight>& lights() const { return m_lights; }
  /// area lights ([[lights]] kind = "sphere"); each is also a visible emissive sphere object
  const std::vector<SphereLight>& sphere_lights() const { return m_sphere_lights; }
  const std::vector<Medium>& media() const { return m_media; }
  const std::vector<Material>& materials() const { return m_materials; }
  const std::vector<SceneObject>& objects() const { return m_objects; }
  const std::vector<Primitive>& primitives() const { return m_primitives; }
  const Bvh& bvh() const { return m_bvh; }
  Rgb ambient() const { return m_ambient; }
  Rgb background() const { return m_background; }
  /// what escaping rays see ([environment]; constant: background())
  const Environment& environment() const { return m_environment; }
  /// medium the camera sits in (index into media())
  std::uint32_t camera_medium() const { return m_camera_medium; }
  const SceneStatistics& statistics() const { return m_stats; }
  /// whether render() uses spectral transport ([image] spectral, resolved by build_scene)
  bool spectral() const { return m_spectral; }

  /// Closest hit with 0 < t < ray.t_max.
  bool intersect(const Ray& ray, Hit& hit) const;
  /// Whether anything (opaque or dielectric, except index-matched dielectrics) lies on the ray
  /// for 0 < t < ray.t_max.
  bool occluded(const Ray& ray) const;
  /// The surface at `hit` along `ray`.
  SurfaceInteraction interaction(const Ray& ray, const Hit& hit) const;
  /// Whether no shadow ray from `origin` to sphere light `light` can be occluded: no plane
  /// separates them and no primitive's box (but the light's own sphere) meets their shadow cone
  /// (render/geometry/shadow_cone.h). Conservative: false means "maybe", and the rays decide.
  /// `origin` is the rays' common origin (offset_ray_origin of the shading point).
  bool light_unoccluded(const Vec3& origin, std::size_t light) const;

 private:
  friend Scene build_scene(const SceneDescription&);
  friend class SceneBuilder;
  ImageSettings m_settings;
  CausticSettings m_caustics;
  Camera m_camera;
  std::vector<PointLight> m_lights;
  std::vector<SphereLight> m_sphere_lights;
  Rgb m_ambient, m_background;
  Environment m_environment;
  std::vector<Medium> m_media;
  std::vector<Material> m_materials;
  std::vector<SceneObject> m_objects;
  std::vector<Primitive> m_primitives;
  struct NormalSet {
    std::vector<Vec3> normals;
    std::vector<std::array<std::uint32_t, 3>> indices;
    /// SurfaceInteraction::curvature of each triangle, computed once at build (it depends on
    /// the triangle alone; 6 square roots and 3 divisions per hit otherwise)
    std::vector<float> curvature;
  };
  std::vector<NormalSet> m_normal_sets;
  std::vector<std::uint32_t> m_planes;  // object indices
  /// unit geometric normal of each triangle primitive (leaf order; zero for other shapes),
  /// computed once at build: a cross product, a square root and a division fewer per hit
  std::vector<Vec3> m_triangle_normals;
  Bvh m_bvh;
  // BVH leaves made only of triangles, packed four-wide; m_leaf_block[first primitive of a leaf]
  // is its index in m_leaf_triangles, or kNoBlock for leaves with other shapes.
  static constexpr std::uint32_t kNoBlock = 0xffffffffu;
  std::vector<Triangle4> m_leaf_triangles;
  std::vector<std::uint32_t> m_leaf_block;
  std::uint32_t m_camera_medium = 0;
  bool m_spectral = false;
  bool m_any_index_matched = false;
  SceneStatistics m_stats;
};

/// Validates `desc` (names, geometry, closed dielectric meshes), loads its meshes and builds the
/// BVH. Throws thaw::UserError naming the scene file (or object label) and the problem.
Scene build_scene(const SceneDescription& desc);

}  // namespace thaw::render
