// Photon cones; see light_cone.h.
#include "render/photon/light_cone.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thaw::render::photon {

namespace {

constexpr double kPiD = 3.14159265358979323846;

/// Bounding sphere of the primitives of object `object`: centre of their box, radius to the
/// farthest vertex (spheres and boxes exactly).
BoundingSphere object_bounds(const Scene& scene, std::uint32_t object) {
  const float inf = std::numeric_limits<float>::infinity();
  Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
  auto grow = [&](const Vec3& p) {
    lo = min(lo, p);
    hi = max(hi, p);
  };
  for (const Primitive& p : scene.primitives()) {
    if (p.object != object) continue;
    if (p.kind == PrimitiveKind::sphere) {
      const Vec3 r{p.b.x, p.b.x, p.b.x};
      grow(p.a - r);
      grow(p.a + r);
    } else if (p.kind == PrimitiveKind::box) {
      grow(p.a);
      grow(p.b);
    } else {
      grow(p.a);
      grow(p.b);
      grow(p.c);
    }
  }
  BoundingSphere s;
  if (!(lo.x <= hi.x)) return s;
  s.center = (lo + hi) * 0.5f;
  double r2 = 0;
  auto reach = [&](const Vec3& p) { r2 = std::max(r2, double(dot(p - s.center, p - s.center))); };
  for (const Primitive& p : scene.primitives()) {
    if (p.object != object) continue;
    if (p.kind == PrimitiveKind::sphere) {
      const double d = length(p.a - s.center) + p.b.x;
      r2 = std::max(r2, d * d);
    } else if (p.kind == PrimitiveKind::box) {
      reach(p.a);
      reach(p.b);
    } else {
      reach(p.a);
      reach(p.b);
      reach(p.c);
    }
  }
  // Widened by a few ulps so that rounding never lets a surface point fall outside.
  s.radius = static_cast<float>(std::sqrt(r2) * (1 + 1e-6)) +
             1e-6f * (std::fabs(s.center.x) + std::fabs(s.center.y) + std::fabs(s.center.z));
  return s;
}

bool inside(const BoundingSphere& a, const BoundingSphere& b) {
  return double(length(a.center - b.center)) + a.radius <= double(b.radius);
}

}  // namespace

std::vector<BoundingSphere> dielectric_targets(const Scene& scene) {
  std::vector<BoundingSphere> all;
  std::vector<std::uint32_t> object;
  for (std::uint32_t i = 0; i < scene.objects().size(); ++i) {
    const SceneObject& o = scene.objects()[i];
    if (!o.dielectric || o.index_matched) continue;
    const BoundingSphere s = object_bounds(scene, i);
    if (s.radius <= 0) continue;
    all.push_back(s);
    object.push_back(i);
  }
  // Object i is nested in object j when its sphere lies in j's and its outside medium is j's
  // inside medium (the water core in the ice shell): light reaches it only through j.
  std::vector<BoundingSphere> kept;
  for (std::size_t i = 0; i < all.size(); ++i) {
    bool nested = false;
    for (std::size_t j = 0; j < all.size() && !nested; ++j)
      nested = i != j && inside(all[i], all[j]) &&
               scene.objects()[object[i]].outside == scene.objects()[object[j]].inside;
    if (!nested) kept.push_back(all[i]);
  }
  return kept;
}

void tangent_frame(const Vec3& n, Vec3& t1, Vec3& t2) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  t1 = Vec3{1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
  t2 = Vec3{b, sign + n.y * n.y * a, -n.y};
}

Vec3 LightCone::direction(double u1, double u2) const {
  const double cos_t = 1.0 - u1 * (1.0 - cos_half);
  const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
  const double phi = 2.0 * kPiD * u2;
  Vec3 t1, t2;
  tangent_frame(axis, t1, t2);
  const Vec3 d =
      t1 * float(sin_t * std::cos(phi)) + t2 * float(sin_t * std::sin(phi)) + axis * float(cos_t);
  return normalize(d);
}

Vec3 emission_point(const Emitter& emitter, const Vec3& direction, double u1, double u2) {
  if (!(emitter.radius > 0.0f)) return emitter.position;
  // Concentric map of [0,1)^2 onto the unit disc (Shirley & Chiu 1997).
  const double a = 2.0 * u1 - 1.0, b = 2.0 * u2 - 1.0;
  double x = 0, y = 0;
  if (a != 0.0 || b != 0.0) {
    const double r = std::fabs(a) > std::fabs(b) ? a : b;
    const double phi =
        std::fabs(a) > std::fabs(b) ? kPiD / 4 * (b / a) : kPiD / 2 - kPiD / 4 * (a / b);
    x = r * std::cos(phi);
    y = r * std::sin(phi);
  }
  Vec3 t1, t2;
  tangent_frame(direction, t1, t2);
  const double forward = std::sqrt(std::max(0.0, 1.0 - x * x - y * y)) + 1e-4;
  return emitter.position +
         (t1 * float(x) + t2 * float(y) + direction * float(forward)) * emitter.radius;
}

bool LightCone::contains(const Vec3& d) const {
  return cos_half <= -1.0 || double(dot(d, axis)) >= cos_half;
}

std::vector<Emitter> emitters(const Scene& scene) {
  std::vector<Emitter> out;
  for (const PointLight& l : scene.lights())
    out.push_back({l.position, 0.0f, l.radiance, l.inverse_square});
  constexpr float kPi = 3.14159265358979323846f;
  for (const SphereLight& l : scene.sphere_lights())
    out.push_back({l.center, l.radius, l.radiance * (kPi * l.radius * l.radius), l.inverse_square});
  return out;
}

std::vector<LightCone> light_cones(const std::vector<Emitter>& emitters,
                                   const std::vector<BoundingSphere>& targets) {
  std::vector<std::uint32_t> order(targets.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return targets[a].radius < targets[b].radius;
  });
  std::vector<LightCone> cones;
  for (std::uint32_t li = 0; li < emitters.size(); ++li) {
    const Emitter& light = emitters[li];
    if (light.intensity.max_component() <= 0.0f) continue;
    for (const std::uint32_t ti : order) {
      const BoundingSphere& t = targets[ti];
      LightCone c;
      c.emitter = li;
      c.target_index = ti;
      c.apex = light.position;
      c.target = t;
      c.cone_radius = double(t.radius) + double(light.radius);
      const Vec3 to = t.center - light.position;
      const double dist = length(to);
      if (dist <= c.cone_radius) {
        c.axis = Vec3{0, 1, 0};
        c.cos_half = -1;
        c.distance = std::max(dist, double(t.radius));
      } else {
        c.axis = to / float(dist);
        const double sin_half = c.cone_radius / dist;
        c.cos_half = std::sqrt(std::max(0.0, 1.0 - sin_half * sin_half));
        c.distance = dist;
      }
      c.solid_angle_sr = 2.0 * kPiD * (1.0 - c.cos_half);
      cones.push_back(c);
    }
  }
  return cones;
}

}  // namespace thaw::render::photon
