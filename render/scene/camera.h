#pragma once
// Pinhole camera: position, look-at point, up vector, vertical field of view. Pixel (0, 0) is the
// top-left corner; a sample at continuous image position (x, y) in pixels maps to a unit ray
// direction. Right-handed world, +Y up by convention of the scenes.
#include <cmath>

#include "render/math/ray.h"

namespace thaw::render {

class Camera {
 public:
  Camera() = default;
  /// `up` need not be orthogonal to the view direction; fov in degrees; width, height in pixels.
  Camera(const Vec3& position, const Vec3& look_at, const Vec3& up, double vertical_fov_deg,
         int width, int height)
      : m_origin(position) {
    const Vec3 forward = normalize(look_at - position);
    const Vec3 right = normalize(cross(forward, up));
    const Vec3 true_up = cross(right, forward);
    const double tan_half = std::tan(vertical_fov_deg * 0.5 * 3.14159265358979323846 / 180.0);
    const float half_h = static_cast<float>(tan_half);
    const float half_w = static_cast<float>(tan_half * width / height);
    m_forward = forward;
    m_dx = right * (2.0f * half_w / static_cast<float>(width));
    m_dy = true_up * (-2.0f * half_h / static_cast<float>(height));
    m_top_left = forward - right * half_w + true_up * half_h;
  }

  /// Primary ray through continuous image position (x, y) [pixels], unit direction.
  Ray generate(float x, float y) const {
    return Ray{m_origin, normalize(m_top_left + m_dx * x + m_dy * y)};
  }
  const Vec3& position() const { return m_origin; }
  /// Angle a pixel subtends at the image centre [rad] (the spread of a ray cone through it).
  float pixel_angle() const { return length(m_dy); }

 private:
  Vec3 m_origin, m_forward, m_dx, m_dy, m_top_left;
};

}  // namespace thaw::render
