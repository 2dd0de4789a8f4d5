#pragma once
// The radiance of directions that leave the scene: a constant background colour, a procedural
// sky (a gradient from the horizon to the zenith above, a ground colour below, joined smoothly
// across the horizon) or a lat-long HDR image (latlong_map.h, turned about +y), so that ice and
// water refract and reflect a surround with light and dark parts, which is what makes transparent
// bodies read as transparent. A sky may carry rectangular panels (soft boxes, windows) that the
// ice reflects and refracts. Seen by rays that escape (camera, reflected, refracted); with
// `light_surfaces` it also lights matte and phong surfaces through its irradiance (irradiance_sh.h;
// occlusion: environment_lighting.h), and with `haze_distance` it is the colour far surfaces fade
// into (haze_radiance). Knows nothing about scenes or rays beyond a direction.
#include <algorithm>
#include <cmath>
#include <memory>

#include <vector>

#include "render/light/irradiance_sh.h"
#include "render/light/latlong_map.h"
#include "render/math/color.h"
#include "render/math/vec3.h"

namespace thaw::render {

/// A rectangle of uniform radiance in the sky, as seen from the scene (a soft box, a window): the
/// directions d with c = dot(d, centre) > 0 whose gnomonic coordinates x = dot(d, right) / c,
/// y = dot(d, top) / c lie within +-half_width, +-half_height (tangents of the half-angles),
/// with a linear ramp `edge` wide (tangent units) centred on each border: no aliasing seam.
struct EnvironmentPanel {
  Vec3 centre, right, top;
  float half_width = 0.1f, half_height = 0.1f, edge = 0.01f;
  Rgb radiance;

  /// The panel's share of direction d: 1 inside, 0 outside, a ramp across the border.
  float coverage(const Vec3& d) const {
    const float c = dot(d, centre);
    if (c <= 0.0f) return 0.0f;
    const float x = std::abs(dot(d, right)) / c, y = std::abs(dot(d, top)) / c;
    const float fx = std::clamp((half_width - x) / edge + 0.5f, 0.0f, 1.0f);
    const float fy = std::clamp((half_height - y) / edge + 0.5f, 0.0f, 1.0f);
    return fx * fy;
  }
};

struct Environment {
  enum class Kind { constant, sky, latlong };
  Kind kind = Kind::constant;
  /// constant: the colour; sky: unused
  Rgb background{0.0f, 0.0f, 0.0f};
  /// sky: radiance at the zenith, at the horizon and of the ground (linear RGB)
  Rgb zenith{0.15f, 0.3f, 0.65f}, horizon{0.8f, 0.85f, 0.9f}, ground{0.25f, 0.22f, 0.2f};
  /// sky: unit vector to the zenith
  Vec3 up{0.0f, 1.0f, 0.0f};
  /// sky: how fast the gradient leaves the horizon colour: L = horizon + (zenith - horizon)
  /// * sin(elevation)^exponent, exponent in (0, 10]
  float exponent = 0.5f;
  /// latlong: the image (shared by the frames of a film), its scale, and the cosine and sine of
  /// its turn about +y (right-handed: a feature at map direction m is seen at R_y(angle) m; +90
  /// degrees brings the image's centre, -z, to -x)
  std::shared_ptr<const LatLongMap> map;
  float map_scale = 1.0f;
  float map_cos = 1.0f, map_sin = 0.0f;
  /// sky: panels added over the gradient
  std::vector<EnvironmentPanel> panels;
  /// whether the environment lights matte and phong surfaces (environment_lighting.h), with
  /// `occlusion_samples` rays per shading point and camera sample where something opaque may hide
  /// part of it, and the unoccluded irradiance from `irradiance_sh` (set by build_scene)
  bool light_surfaces = false;
  /// aerial perspective: distance [scene units] over which a surface seen through the camera's
  /// medium fades to the sky at the horizon by exp(-t / haze_distance); 0 = none
  float haze_distance = 0.0f;
  int occlusion_samples = 16;
  IrradianceSH irradiance_sh;

  /// Radiance arriving from unit direction `d` (of light travelling along -d).
  Rgb radiance(const Vec3& d) const {
    if (kind == Kind::constant) return background;
    if (kind == Kind::latlong) {
      // Into the map's frame: R_y(-angle) d.
      const Vec3 m{map_cos * d.x - map_sin * d.z, d.y, map_sin * d.x + map_cos * d.z};
      return map->radiance(m) * map_scale;
    }
    Rgb l = sky_gradient(d);
    for (const EnvironmentPanel& p : panels) {
      const float c = p.coverage(d);
      if (c > 0.0f) l += p.radiance * c;
    }
    return l;
  }

  /// The haze's radiance along unit direction d: the environment at the horizon below or above
  /// d (panels left out), which is what an endless horizontal path through the haze shows, so a
  /// surface far away fades exactly into the sky behind it at the horizon.
  Rgb haze_radiance(const Vec3& d) const {
    if (kind == Kind::constant) return background;
    if (kind == Kind::sky) return horizon;  // the gradient at elevation 0, in every azimuth
    const Vec3 h = d - up * dot(d, up);
    const float len = length(h);
    const Vec3 dir = len > 1e-6f ? h / len : Vec3{1.0f, 0.0f, 0.0f};
    return radiance(dir);
  }

  /// sky: the gradient without panels.
  Rgb sky_gradient(const Vec3& d) const {
    const float s = dot(d, up);  // sin(elevation)
    if (s >= 0.0f) {
      // The default exponent's power is a square root (the same value; powf was 1.3 % of a
      // default-film frame: the sky behind each sphere light's cap at every shading point).
      const float e = std::min(s, 1.0f);
      const float t = exponent == 0.5f ? std::sqrt(e) : std::pow(e, exponent);
      return horizon * (1.0f - t) + zenith * t;
    }
    // Below: the ground, reached from the horizon colour within 2 degrees (no hard seam).
    const float t = std::min(-s / 0.035f, 1.0f);
    return horizon * (1.0f - t) + ground * t;
  }
};

}  // namespace thaw::render
