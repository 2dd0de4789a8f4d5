// Light from the environment on diffuse surfaces; see environment_lighting.h.
#include "render/light/environment_lighting.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "render/light/sphere_light.h"

namespace thaw::render {
namespace {

/// Unit vectors t, b completing n to a right-handed orthonormal frame (Duff et al. 2017).
void orthonormal_frame(const Vec3& n, Vec3& t, Vec3& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z), c = n.x * n.y * a;
  t = Vec3{1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = Vec3{c, sign + n.y * n.y * a, -n.y};
}

/// Cosine-distributed direction about n from the unit square point u (Malley's method over
/// Shirley & Chiu's concentric disc map): density cos / pi.
Vec3 cosine_direction(const Vec3& n, sampling::Point2 u) {
  const float x = 2.0f * u.x - 1.0f, y = 2.0f * u.y - 1.0f;
  float r = 0.0f, phi = 0.0f;
  if (x != 0.0f || y != 0.0f) {
    constexpr float kQuarterPi = std::numbers::pi_v<float> / 4;
    if (std::abs(x) > std::abs(y)) {
      r = x;
      phi = kQuarterPi * (y / x);
    } else {
      r = y;
      phi = 2.0f * kQuarterPi - kQuarterPi * (x / y);
    }
  }
  const float dx = r * std::cos(phi), dy = r * std::sin(phi);
  const float dz = std::sqrt(std::max(0.0f, 1.0f - dx * dx - dy * dy));
  Vec3 t, b;
  orthonormal_frame(n, t, b);
  return normalize(t * dx + b * dy + n * dz);
}

float luminance(const Rgb& c) {
  return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

}  // namespace

EnvironmentOccluders::EnvironmentOccluders(const Scene& scene) : m_objects(scene.objects()) {
  const auto& objects = scene.objects();
  m_occluder.assign(objects.size(), 1);
  std::vector<char> light_material(scene.materials().size(), 0);
  for (const SphereLight& l : scene.sphere_lights()) light_material[l.material] = 1;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const SceneObject& o = objects[i];
    if (o.dielectric || (o.shape == ObjectDescription::Shape::sphere && light_material[o.material]))
      m_occluder[i] = 0;
    else if (o.shape == ObjectDescription::Shape::plane)
      m_planes.push_back(static_cast<std::uint32_t>(i));
  }
  std::vector<Aabb> boxes(objects.size());
  for (const Primitive& prim : scene.primitives()) {
    if (!m_occluder[prim.object]) continue;
    Aabb& box = boxes[prim.object];
    switch (prim.kind) {
      case PrimitiveKind::triangle:
        box.extend(prim.a);
        box.extend(prim.b);
        box.extend(prim.c);
        break;
      case PrimitiveKind::sphere: {
        const Vec3 r{prim.b.x, prim.b.x, prim.b.x};
        box.extend(prim.a - r);
        box.extend(prim.a + r);
        break;
      }
      case PrimitiveKind::box:
        box.extend(prim.a);
        box.extend(prim.b);
        break;
    }
  }
  for (std::size_t i = 0; i < objects.size(); ++i) {
    if (boxes[i].empty()) continue;
    const auto shape = objects[i].shape;
    m_bounds.push_back(
        {boxes[i], static_cast<std::uint32_t>(i),
         shape == ObjectDescription::Shape::sphere || shape == ObjectDescription::Shape::box});
  }
}

bool EnvironmentOccluders::may_occlude(const Vec3& origin, const Vec3& n,
                                       std::uint32_t object) const {
  // A plane hides nothing of the hemisphere only when it is parallel to the tangent plane and
  // the hemisphere faces away from it (the floor under its own points); up to 1e-6 in the
  // normals' cosine: directions within 1.4e-3 rad of the tangent plane, of cosine weight 1e-6.
  for (const std::uint32_t i : m_planes) {
    if (!m_occluder[i]) continue;
    const SceneObject& plane = m_objects[i];
    const float side = dot(origin - plane.plane_point, plane.plane_normal) >= 0.0f ? 1.0f : -1.0f;
    if (dot(n, plane.plane_normal) * side < 1.0f - 1e-6f) return true;
  }
  for (const Bounds& b : m_bounds) {
    if (b.convex && b.object == object) continue;
    for (int k = 0; k < 8; ++k) {
      const Vec3 corner{(k & 1) ? b.box.hi.x : b.box.lo.x, (k & 2) ? b.box.hi.y : b.box.lo.y,
                        (k & 4) ? b.box.hi.z : b.box.lo.z};
      if (dot(corner - origin, n) > 0.0f) return true;
    }
  }
  return false;
}

bool EnvironmentOccluders::occluded(const Scene& scene, Ray ray) const {
  // Past dielectrics and light spheres, hit by hit (a ray crosses a handful of interfaces).
  for (int crossings = 0; crossings < 64; ++crossings) {
    Hit hit;
    if (!scene.intersect(ray, hit)) return false;
    const SurfaceInteraction si = scene.interaction(ray, hit);
    if (m_occluder[si.object]) return true;
    ray = Ray{offset_ray_origin(si.p, si.p_error, si.ng, ray.direction), ray.direction};
  }
  return true;  // a maze of interfaces: taken as hidden
}

Rgb environment_irradiance(const Scene& scene, const EnvironmentOccluders& occluders, const Vec3& p,
                           const Vec3& p_error, const Vec3& ng, const Vec3& ns,
                           std::uint32_t object, int depth, const CameraSampleContext& ctx,
                           std::uint64_t& rays) {
  const Environment& env = scene.environment();
  Rgb e = env.irradiance_sh.irradiance(ns);
  // Sphere lights hide their cap of the environment: that cone holds the light's own radiance,
  // which the light's direct term brings.
  for (const SphereLight& light : scene.sphere_lights()) {
    const Vec3 to_c = light.center - p;
    const double d2 = double(dot(to_c, to_c)), r2 = double(light.radius) * light.radius;
    if (!(d2 > r2)) continue;
    const double d = std::sqrt(d2);
    const double cap = sphere_irradiance_per_radiance(double(dot(ns, to_c)) / d, r2 / d2);
    if (cap > 0.0) e += env.radiance(to_c / static_cast<float>(d)) * static_cast<float>(-cap);
  }
  e = Rgb{std::max(e.r, 0.0f), std::max(e.g, 0.0f), std::max(e.b, 0.0f)};
  if (e.is_black()) return e;
  const Vec3 origin = offset_ray_origin(p, p_error, ng, ng);
  if (!occluders.may_occlude(origin, ns, object)) return e;
  // Something opaque may hide part of the sky: the luminance-weighted visible share of the
  // cosine-distributed samples (cos / pdf = pi is the same for all and cancels).
  const sampling::PixelSampler fallback(0, 0);
  const CameraSampleContext camera = ctx.sampler ? ctx : CameraSampleContext{&fallback, 0};
  const auto n = static_cast<std::uint32_t>(env.occlusion_samples);
  const std::uint32_t n_max = penumbra_samples(n);
  const std::uint32_t dim = light_dimension(depth, scene.sphere_lights().size());
  double all = 0.0, visible = 0.0;
  int seen = 0, hidden = 0;
  for (std::uint32_t j = 0; j < n_max; ++j) {
    if (j == n && (seen == 0 || hidden == 0)) break;
    // The first n of camera sample s are points s n .. s n + n - 1 of the pair: the pixel's
    // first S n rays together form one net (stratified across its camera samples, as the sphere
    // lights' shadow rays: light_sampling.h); the rest come from the penumbra pair.
    const sampling::Point2 u = j < n ? camera.sampler->get_2d(camera.sample_index * n + j, dim)
                                     : camera.sampler->get_2d(camera.sample_index * n_max + j,
                                                              dim + kPenumbraDimensionOffset);
    const Vec3 wi = cosine_direction(ns, u);
    if (dot(wi, ng) <= 0.0f) continue;
    // + a floor so that a black part of the sky still counts as directions
    const double w = double(luminance(env.radiance(wi))) + 1e-6;
    all += w;
    ++rays;
    if (occluders.occluded(scene, Ray{offset_ray_origin(p, p_error, ng, wi), wi})) {
      ++hidden;
      continue;
    }
    ++seen;
    visible += w;
  }
  const double fraction = all > 0.0 ? visible / all : 1.0;
  return e * static_cast<float>(fraction);
}

}  // namespace thaw::render
