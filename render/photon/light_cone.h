#pragma once
// Where photons are sent: the cones from each light to the bounding spheres of the scene's
// dielectric objects (the only objects that can make a caustic). Index-matched dielectrics
// (Scene: SceneObject::index_matched) are not targets, nor are objects nested in another (inside
// its bounding sphere, with its inside medium outside them: the ice shell's water core); an
// object merely standing inside another's sphere (the ice in its puddle ring) stays a target. A
// light inside a target sphere gets the whole sphere of directions. Sampling is uniform in solid
// angle; the cones of one light may overlap, so a direction belongs to the first cone that contains
// it and the others discard it: together they sample the union once. A light's cones are ordered by
// target size, smallest first, so the overlap (the ice standing in its puddle) goes to the
// finer target. A sphere light of radius a emits from its whole disc as seen along each
// direction, so its cones are aimed at the targets' spheres grown by a (every ray from the
// light that can reach the target has its direction in that cone). Knows nothing about photon
// power.
#include <cstdint>
#include <vector>

#include "render/math/color.h"
#include "render/math/vec3.h"
#include "render/scene/scene.h"

namespace thaw::render::photon {

struct BoundingSphere {
  Vec3 center;
  /// [scene units]
  float radius = 0;
};

/// Bounding spheres of the dielectric objects that are not index matched and not nested in
/// another (see above), in object order.
std::vector<BoundingSphere> dielectric_targets(const Scene& scene);

/// A light as the photon pass sees it: point lights (radius 0), then sphere lights.
struct Emitter {
  Vec3 position;
  /// sphere lights: radius [scene units]; 0 for point lights
  float radius = 0;
  /// colour * intensity (a sphere light's L pi a^2)
  Rgb intensity;
  bool inverse_square = false;
};

/// Scene::lights() then Scene::sphere_lights().
std::vector<Emitter> emitters(const Scene& scene);

struct LightCone {
  /// index into the emitters
  std::uint32_t emitter = 0;
  /// index into the targets
  std::uint32_t target_index = 0;
  Vec3 apex;
  /// unit axis from the light to the target's centre
  Vec3 axis;
  /// cosine of the half-angle; -1 when the light is inside the target (all directions)
  double cos_half = 1;
  /// 2 pi (1 - cos_half) [sr]
  double solid_angle_sr = 0;
  /// light to target centre [scene units] (at least the target's radius)
  double distance = 0;
  BoundingSphere target;
  /// the sphere the cone is aimed at: the target's radius plus the emitter's
  double cone_radius = 0;

  /// Direction for two uniform numbers in [0, 1): uniform in solid angle inside the cone
  /// (cos theta = 1 - u1 (1 - cos_half), phi = 2 pi u2; an area-preserving map, so
  /// low-discrepancy points stay low-discrepancy on the sphere).
  Vec3 direction(double u1, double u2) const;
  bool contains(const Vec3& direction) const;
};

/// Unit vectors t1, t2 completing the unit vector n to a right-handed orthonormal frame (Duff et
/// al. 2017, "Building an orthonormal basis, revisited").
void tangent_frame(const Vec3& n, Vec3& t1, Vec3& t2);

/// Where a photon of direction `direction` leaves an emitter, for two uniform numbers in [0, 1):
/// a point light's position; for a sphere light, a point of the disc of the sphere seen along
/// `direction` (Shirley & Chiu 1997 concentric map: area preserving, so low-discrepancy points
/// stay so), moved forward onto the sphere's surface (and 1e-4 of its radius beyond, so that
/// the photon does not hit the light's own visible sphere).
Vec3 emission_point(const Emitter& emitter, const Vec3& direction, double u1, double u2);

/// One cone per (emitter, target), emitters in order, targets by increasing radius within an
/// emitter (ties in target order). Emitters of zero intensity get none.
std::vector<LightCone> light_cones(const std::vector<Emitter>& emitters,
                                   const std::vector<BoundingSphere>& targets);

}  // namespace thaw::render::photon
