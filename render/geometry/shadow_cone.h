#pragma once
// The region swept by the shadow rays from one origin to a spherical light: every segment from
// the apex o to a point of the ball (centre c, radius R) lies in their convex hull, which lies in
// the cone of apex o, axis towards c and half-angle asin(R / |c - o|), cut at |c - o| + R along
// the axis. Conservative tests of spheres and boxes against that cone ("may touch": false only
// when nothing of the shape can meet any of the segments), so that a shading point whose cone
// touches nothing needs no shadow ray at all (Scene::light_unoccluded). A slack, added to every
// tested radius, absorbs the float rounding of the tests. Knows nothing about scenes or lights.
#include <algorithm>
#include <cmath>

#include "render/math/vec3.h"

namespace thaw::render {

class ShadowCone {
 public:
  /// `apex` outside the ball (|center - apex| > radius), `slack` >= 0 [scene units].
  ShadowCone(const Vec3& apex, const Vec3& center, float radius, float slack)
      : m_apex(apex), m_slack(slack) {
    const Vec3 v = center - apex;
    m_distance = length(v);
    m_axis = v / m_distance;
    m_sin = std::min(radius / m_distance, 1.0f);
    m_cos = std::sqrt(1.0f - m_sin * m_sin);
    m_far = m_distance + radius;
  }

  /// Whether the ball (c, rho) may meet the cone: within rho of the apex, or within the axial
  /// range [-rho, far + rho] and at an angle from the axis below theta + asin(rho / |c - o|)
  /// (the cone grown by the ball's angular radius).
  bool may_touch_sphere(const Vec3& c, float rho) const {
    rho += m_slack;
    const Vec3 v = c - m_apex;
    const float len2 = dot(v, v);
    if (len2 <= rho * rho) return true;
    const float x = dot(v, m_axis);
    if (x < -rho || x > m_far + rho) return false;
    const float len = std::sqrt(len2);
    const float sin_phi = rho / len, cos_phi = std::sqrt(1.0f - sin_phi * sin_phi);
    // cos(theta + phi); theta, phi <= pi / 2, so theta + phi <= pi and cos is decreasing there.
    const float cos_sum = m_cos * cos_phi - m_sin * sin_phi;
    return x >= cos_sum * len;
  }

  /// Whether the box [lo, hi] may meet the cone: its circumscribed ball does.
  bool may_touch_box(const Vec3& lo, const Vec3& hi) const {
    return may_touch_sphere((lo + hi) * 0.5f, 0.5f * length(hi - lo));
  }

  const Vec3& apex() const { return m_apex; }
  const Vec3& axis() const { return m_axis; }

 private:
  Vec3 m_apex, m_axis;
  float m_distance = 0, m_sin = 0, m_cos = 1, m_far = 0, m_slack = 0;
};

}  // namespace thaw::render
