#pragma once
// Where photons are sent: the cones from each point light to the bounding spheres of the scene's
// dielectric objects (the only objects that can make a caustic). Index-matched dielectrics
// (Scene: SceneObject::index_matched) are not targets, and a bounding sphere inside another is
// dropped (the ice shell's water core is inside the shell's sphere). A light inside a target
// sphere gets the whole sphere of directions. Sampling is uniform in solid angle; the cones of
// one light may overlap, so a direction belongs to the first cone (in order) that contains it and
// the others discard it: together they sample the union once. Knows nothing about photon power.
#include <cstdint>
#include <vector>

#include "render/math/vec3.h"
#include "render/scene/scene.h"

namespace thaw::render::photon {

struct BoundingSphere {
  Vec3 center;
  /// [scene units]
  float radius = 0;
};

/// Bounding spheres of the dielectric objects that are not index matched, in object order, with
/// every sphere that lies inside another one removed.
std::vector<BoundingSphere> dielectric_targets(const Scene& scene);

struct LightCone {
  /// index into Scene::lights()
  std::uint32_t light = 0;
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

  /// Direction for two uniform numbers in [0, 1): uniform in solid angle inside the cone
  /// (cos theta = 1 - u1 (1 - cos_half), phi = 2 pi u2; an area-preserving map, so
  /// low-discrepancy points stay low-discrepancy on the sphere).
  Vec3 direction(double u1, double u2) const;
  bool contains(const Vec3& direction) const;
};

/// One cone per (light, target), lights in order, targets in order within a light. Lights of
/// zero intensity get none.
std::vector<LightCone> light_cones(const Scene& scene, const std::vector<BoundingSphere>& targets);

}  // namespace thaw::render::photon
