#pragma once
// Whitted shading (Whitted 1980), written once for every radiance type: RGB triples and sampled
// spectra (Mitsuba 3's "variants", here a class template over the concrete tracer, CRTP). One ray
// tree per camera sample:
// - dielectric interfaces between named media: exact Fresnel split (R reflected, 1 - R
//   transmitted), Snell refraction, total internal reflection, the medium carried by every ray
//   (a ray reaching an interface from a side whose label differs counts as a medium mismatch),
//   Beer-Lambert absorption along each segment in an absorbing medium (per wavelength in the
//   spectral variant, per channel in RGB);
// - metal: tinted mirror; matte/phong: ambient + direct light (point lights with hard shadows,
//   sphere lights with soft shadows from stratified low-discrepancy samples) + Phong highlight,
//   and the classic reflect/transmit terms; emissive: its emission.
// The tree is cut at max_depth and where a branch's weight falls below min_weight (POV-Ray's
// adaptive depth control). Settings come from the Scene in the constructor.
//
// Extension points (one function each):
//   background()       radiance of a direction that leaves the scene (environment, sky)
//   add_direct_light() direct light at a diffuse hit, one loop over the scene's lights
//   diffuse()          adds the caustic irradiance E of the frame's photon map: albedo kd E
// The tracer (Derived) supplies what depends on the radiance type; see the "Derived provides"
// list below. Knows nothing about pixels, tiles, films or files.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <vector>

#include "render/integrator/phase_function.h"
#include "render/light/environment_lighting.h"
#include "render/light/environment_sampler.h"
#include "render/light/light_sampling.h"
#include "render/material/fresnel.h"
#include "render/material/microfacet.h"
#include "render/photon/caustic_map.h"
#include "render/photon/photon_tracer.h"
#include "render/scene/scene.h"

namespace thaw::render {

/// A dielectric interface as ray direction d meets it: the medium it comes from and goes to, the
/// normals turned to face d's side (a shading normal facing away replaced by the geometric one).
struct FacingInterface {
  std::uint32_t from, to;
  Vec3 ng, ns;
};

inline FacingInterface facing_interface(const Vec3& d, const SurfaceInteraction& si,
                                        const SceneObject& obj) {
  // The side is decided by the geometric normal, never the shading normal.
  const bool entering = dot(d, si.ng) < 0.0f;
  FacingInterface f{entering ? obj.outside : obj.inside, entering ? obj.inside : obj.outside,
                    entering ? si.ng : -si.ng, entering ? si.ns : -si.ns};
  if (dot(f.ns, d) >= 0.0f) f.ns = f.ng;
  return f;
}

/// Mirror direction about the shading normal, about the geometric one if that would go below.
inline Vec3 reflection_direction(const Vec3& d, const Vec3& ns, const Vec3& ng) {
  const Vec3 dir = reflect(d, ns);
  return dot(dir, ng) <= 0.0f ? reflect(d, ng) : dir;
}

/// Snell's direction with the shading normal, falling back to the geometric one; false on total
/// internal reflection. Normals face the incident side.
inline bool refraction_direction(const Vec3& d, const Vec3& ns, const Vec3& ng, float eta,
                                 Vec3& dir) {
  if (refract(d, ns, eta, dir) && dot(dir, ng) < 0.0f) return true;
  return refract(d, ng, eta, dir);
}

/// First dimension pair of the microfacet normals of rough surfaces (one pair per tree level),
/// apart from the film's and the lights' pairs (render/light/light_sampling.h).
inline constexpr std::uint32_t kMicrofacetDimension = 0x20000u;

/// First dimension pair (and 1D dimension) of volume scattering's free paths and directions (one
/// per tree level).
inline constexpr std::uint32_t kScatteringDimension = 0x30000u;

/// First dimension pair of next-event estimation at scattering events: one pair per tree level
/// and sphere light (level * 64 + light).
inline constexpr std::uint32_t kScatteringLightDimension = 0x38000u;

/// Dielectric interfaces a scattering event's shadow ray may cross before it counts as blocked.
inline constexpr int kMaxShadowCrossings = 16;

/// How a point light meets a surface point: behind it (no shadow ray cast), shadowed, or seen.
enum class LightVisibility { facing_away, shadowed, seen };

inline bool is_black(float v) {
  return v == 0.0f;
}
inline bool is_black(const SampledSpectrum& s) {
  return s.is_black();
}

/// Derived provides (its hooks may be private if it befriends WhittedShading<Derived>):
///   Radiance, Throughput (what pruning weighs: a scalar in RGB, a spectrum in spectral mode),
///   Reflectance (Fresnel's R: same), Path (what rides along a ray: wavelengths, lane, or nothing);
///   static constexpr bool kAbsorption, kDispersion;
///   Radiance illuminant(Rgb, Path)    a light/background colour as radiance
///   Radiance reflectance(Rgb, Path)   a surface colour (albedo, metal tint)
///   Radiance light_radiance(i, Path), ambient(Path), emission(material index, Path)
///   float weight(Throughput, Path)    pruning weight of a branch
///   Throughput attenuate(Throughput, tint, Path)   throughput after a metal's tint
///   Fresnel fresnel(from, to, cos_i, Path)         R, the relative index, and whether the
///                                                  transmission is dispersive (kDispersion)
///   with kAbsorption: bool absorbs(medium); Radiance transmittance(medium, distance, Path)
///   with kDispersion: void dispersive_transmission(result, d, si, interface, cos_i, depth,
///                                                  beta, T, Path)
template <class Derived>
class WhittedShading {
 public:
  /// `caustics`: the frame's photon map (render/photon/caustic_map.h), or null for none.
  explicit WhittedShading(const Scene& scene, const photon::CausticMap* caustics = nullptr)
      : m_scene(scene),
        m_caustics(caustics && !caustics->empty() ? caustics : nullptr),
        m_max_depth(scene.settings().max_depth),
        m_min_weight(static_cast<float>(scene.settings().min_weight)),
        m_pixel_spread(texture_cone_spread(scene)),
        m_haze_distance(scene.environment().haze_distance) {
    if (scene.environment().light_surfaces) m_environment_occluders.emplace(scene);
    for (const SceneObject& o : scene.objects())
      if (o.dielectric && o.index_matched) m_interfaces_stop_shadow_rays = false;
    for (const PointLight& l : scene.lights())
      m_point_light_medium.push_back(photon::medium_at(scene, l.position));
    for (const Medium& m : scene.media()) {
      m_scattering_per_m.push_back(static_cast<float>(m.optics.scattering_per_m()));
      m_asymmetry.push_back(static_cast<float>(m.optics.asymmetry()));
      m_any_scattering = m_any_scattering || m.optics.scatters();
    }
    for (const SphereLight& l : scene.sphere_lights())
      m_sphere_light_medium.push_back(photon::medium_at(scene, l.center));
    if (m_any_scattering) {
      auto sampler = std::make_shared<const EnvironmentSampler>(scene.environment());
      if (!sampler->empty()) m_environment_sampler = std::move(sampler);
    }
    m_light_material.assign(scene.materials().size(), false);
    for (const SphereLight& l : scene.sphere_lights()) m_light_material[l.material] = true;
  }

  /// Spread angle [rad] of the ray cone of one camera sample (0: textures point-sampled): the
  /// angle of a pixel, so that texture detail finer than a pixel is averaged away before the film
  /// samples it (what aliases into moire otherwise), and the image tends to the same limit at
  /// any sample count.
  static float texture_cone_spread(const Scene& scene) {
    const ImageSettings& st = scene.settings();
    if (!st.texture_filter || st.samples_per_pixel <= 1) return 0.0f;
    return scene.camera().pixel_angle();
  }

  /// The camera sample about to be traced (its pixel's sampler and index): the light samples'
  /// points come from it. Null: pixel (0, 0), sample 0 (single rays traced outside a render).
  void set_camera_sample(const CameraSampleContext* camera) {
    m_camera_sample = camera ? *camera : CameraSampleContext{};
    m_cone = RayCone{0.0f, m_pixel_spread};
  }

  /// Adds the rays traced and medium mismatches met so far to `stats`.
  void add_counts(RenderStats& stats) const {
    stats.rays += m_rays;
    stats.medium_mismatches += m_mismatches;
  }

  /// Radiance arriving along `ray` (unit direction), at tree level `depth` (primary = 1), with
  /// throughput `beta`, travelling in `medium`.
  template <class Throughput, class Path>
  auto trace(const Ray& ray, int depth, const Throughput& beta, std::uint32_t medium,
             const Path& path) {
    using Radiance = typename Derived::Radiance;
    ++m_rays;
    Hit hit;
    const bool found = m_scene.intersect(ray, hit);
    const float sigma_s = m_any_scattering ? m_scattering_per_m[medium] : 0.0f;
    if (!found && sigma_s == 0.0f) {
      // A path from a scattering event that leaves through interfaces alone: the environment's
      // light came by next-event estimation there (scatter_direct_light()).
      Radiance bg = m_after_scatter && m_environment_sampler
                        ? Radiance{}
                        : self().illuminant(background(ray.direction), path);
      if constexpr (Derived::kAbsorption) {
        // Escaping inside an absorbing medium: an infinite path keeps nothing where alpha > 0
        // (a huge finite distance avoids 0 * inf where alpha = 0).
        if (self().absorbs(medium)) bg *= self().transmittance(medium, 1e30, path);
      }
      return bg;
    }
    if (sigma_s > 0.0f) {
      // A scattering medium (sigma_s [1/m], lossless: scattering keeps the throughput). The
      // camera's own rays (not yet scattered) are split, as the Whitted tree splits at an
      // interface: the share Tr = exp(-sigma_s s) that crosses the segment unscattered goes on
      // to the surface, the rest 1 - Tr scatters at a distance drawn from the exponential
      // truncated to the segment (pdf sigma_s exp(-sigma_s t) / (1 - Tr)), so no pixel is a coin
      // flip between the glow and what is seen through the ice. Paths that have scattered are
      // followed analogously: an exponential free path (mean 1 / sigma_s), an event before the
      // surface continuing from there (scatter()).
      const float u = camera_sampler().get_1d(m_camera_sample.sample_index,
                                              kScatteringDimension + std::uint32_t(depth));
      if (!m_path_scattered) {
        const float tr = found ? std::exp(-sigma_s * hit.t) : 0.0f;
        const float p_scatter = 1.0f - tr;
        Radiance l{};
        if (p_scatter > 0.0f && self().weight(beta * p_scatter, path) >= m_min_weight) {
          // Kept 1e-4 of the segment short of the surface (float rounding must not put the
          // event on its far side).
          float t = -std::log1p(-std::min(u * p_scatter, 1.0f - 1e-7f)) / sigma_s;
          if (found) t = std::min(t, hit.t * (1.0f - 1e-4f));
          l = scatter(ray, t, depth, beta * p_scatter, medium, path) * p_scatter;
        }
        if (found && tr > 0.0f && self().weight(beta * tr, path) >= m_min_weight)
          l += surface(ray, hit, depth, beta * tr, medium, path) * tr;
        return l;
      }
      const float t = -std::log(std::max(1.0f - u, 1e-30f)) / sigma_s;
      if (!found || t < hit.t * (1.0f - 1e-4f)) return scatter(ray, t, depth, beta, medium, path);
    }
    return surface(ray, hit, depth, beta, medium, path);
  }

  /// The radiance leaving the surface that `ray` hits (`hit`), seen in `medium`: the segment's
  /// absorption, the object's shading, the haze.
  template <class Throughput, class Path>
  auto surface(const Ray& ray, const Hit& hit, int depth, const Throughput& beta,
               std::uint32_t medium, const Path& path) {
    using Radiance = typename Derived::Radiance;
    Throughput b = beta;
    Radiance segment{};
    bool absorbs = false;
    if constexpr (Derived::kAbsorption) {
      absorbs = self().absorbs(medium);
      if (absorbs) {
        // Beer-Lambert over this segment: |direction| = 1, so t is the distance (scene units = m).
        segment = self().transmittance(medium, hit.t, path);
        b = self().attenuate(b, segment, path);
      }
    }
    const SurfaceInteraction si = m_scene.interaction(ray, hit);
    const SceneObject& obj = m_scene.objects()[si.object];
    // The ray cone's width at this hit; the rays leaving it start from here (restored below).
    const RayCone cone_at_origin = m_cone;
    m_cone.width += m_cone.spread * hit.t;
    Radiance l{};
    if (obj.dielectric) {
      l = dielectric(ray, si, obj, depth, b, medium, path);
    } else {
      const Material& mat = m_scene.materials()[obj.material];
      switch (mat.kind) {
        case Material::Kind::emissive:
          // A sphere light met on a path from a scattering event: its light came already by
          // next-event estimation there (scatter_direct_light()).
          if (!(m_after_scatter && m_light_material[obj.material]))
            l = self().emission(obj.material, path);
          break;
        case Material::Kind::metal: {
          const AfterScatter reset(*this, false);
          l = metal(ray, si, mat, depth, b, medium, path);
          break;
        }
        case Material::Kind::matte:
        case Material::Kind::phong: {
          const AfterScatter reset(*this, false);
          l = diffuse(ray, si, mat, depth, b, medium, path);
          break;
        }
      }
    }
    if constexpr (Derived::kAbsorption) {
      if (absorbs) l *= segment;
    }
    if (m_haze_distance > 0.0f && medium == m_scene.camera_medium()) {
      // Aerial perspective ([environment] haze_distance): the surface fades into the sky at the
      // horizon, which the floor reaches at infinity: no step where sky and floor meet.
      const float fade = std::exp(-hit.t / m_haze_distance);
      l = l * fade + self().illuminant(m_scene.environment().haze_radiance(ray.direction), path) *
                         (1.0f - fade);
    }
    m_cone = cone_at_origin;
    return l;
  }

  /// Colour of the light leaving the scene in `direction` (miss path): the scene's environment,
  /// a constant background or a procedural sky (both variants call this one function).
  Rgb background(const Vec3& direction) const { return m_scene.environment().radiance(direction); }

  /// Point light `light` seen from surface point p (error bound p_error, normals ng, ns facing
  /// the viewer): casts the shadow ray; l, cos_l, dist2 describe the direction to the light.
  LightVisibility light_visibility(const Vec3& p, const Vec3& p_error, const Vec3& ng,
                                   const Vec3& ns, const PointLight& light, Vec3& l, float& cos_l,
                                   float& dist2) {
    const Vec3 to_light = light.position - p;
    dist2 = dot(to_light, to_light);
    if (!(dist2 > 0.0f)) return LightVisibility::facing_away;
    l = to_light / std::sqrt(dist2);
    if (dot(l, ng) <= 0.0f) return LightVisibility::facing_away;  // light behind the surface
    cos_l = dot(ns, l);
    if (cos_l <= 0.0f) return LightVisibility::facing_away;
    const Vec3 origin = offset_ray_origin(p, p_error, ng, l);
    ++m_rays;
    // Unnormalised direction: the light sits at t = 1; stop just short of it.
    return m_scene.occluded(Ray{origin, light.position - origin, 1.0f - 1e-4f})
               ? LightVisibility::shadowed
               : LightVisibility::seen;
  }

 protected:
  Derived& self() { return static_cast<Derived&>(*this); }

  template <class Throughput, class Path>
  auto dielectric(const Ray& ray, const SurfaceInteraction& si, const SceneObject& obj, int depth,
                  const Throughput& beta, std::uint32_t medium, const Path& path) {
    using Radiance = typename Derived::Radiance;
    using Reflectance = typename Derived::Reflectance;
    const Vec3& d = ray.direction;
    const FacingInterface fi = facing_interface(d, si, obj);
    if (medium != fi.from) ++m_mismatches;
    const float cos_i = -dot(d, fi.ns);
    Radiance result{};
    if (depth >= m_max_depth) return result;
    if (obj.alpha > 0.0f) return rough_dielectric(ray, si, obj, fi, depth, beta, path);
    const auto f = self().fresnel(fi.from, fi.to, cos_i, path);
    // Reflected branch: with its own Fresnel reflectance per carried wavelength.
    const Throughput br = beta * f.r;
    if (!is_black(f.r) && self().weight(br, path) >= m_min_weight) {
      const Vec3 dir = reflection_direction(d, fi.ns, fi.ng);
      const Ray next{offset_ray_origin(si.p, si.p_error, fi.ng, dir), dir};
      const ConeBend bend(*this, [&] {
        return SpreadChange{1.0f, 2.0f * normal_spread(si, d, cos_i)};
      });
      // A reflection ends a transmission-only path from a scattering event (AfterScatter).
      const AfterScatter reflected(*this, false);
      result += trace(next, depth + 1, br, fi.from, path) * f.r;
    }
    const Reflectance t = Reflectance(1.0f) - f.r;
    if constexpr (Derived::kDispersion) {
      if (f.dispersive) {
        // The wavelengths part ways: split, adaptive integration or hero (spectral only).
        self().dispersive_transmission(result, d, si, fi, cos_i, depth, beta, t, path);
        return result;
      }
    }
    const Throughput bt = beta * t;
    if (!is_black(t) && self().weight(bt, path) >= m_min_weight) {
      Vec3 dir;
      if (refraction_direction(d, fi.ns, fi.ng, f.eta, dir)) {
        const Ray next{offset_ray_origin(si.p, si.p_error, fi.ng, dir), dir};
        // Snell's law differentiated: d(theta_t) / d(theta_i) = cos_i / (eta cos_t); a tilt of
        // the normal by delta turns the refracted ray by delta (1 - cos_i / (eta cos_t)) towards
        // it: a convex surface into a denser medium (ratio < 1) focuses.
        const ConeBend bend(*this, [&] {
          const float ratio =
              std::abs(cos_i) / (f.eta * std::max(std::abs(dot(dir, fi.ns)), 1e-3f));
          return SpreadChange{ratio, -(1.0f - ratio) * normal_spread(si, d, cos_i)};
        });
        result += trace(next, depth + 1, bt, fi.to, path) * t;
      }
    }
    return result;
  }

  template <class Throughput, class Path>
  auto metal(const Ray& ray, const SurfaceInteraction& si, const Material& mat, int depth,
             const Throughput& beta, std::uint32_t medium, const Path& path) {
    using Radiance = typename Derived::Radiance;
    const Radiance tint = self().reflectance(texture_colour(mat.texture, si, ray.direction), path);
    const Throughput b = self().attenuate(beta, tint, path);
    const float w = self().weight(b, path);
    if (depth >= m_max_depth || w < m_min_weight || w == 0.0f) return Radiance{};
    const Vec3 ng = face_forward(si.ng, -ray.direction);
    const Vec3 ns = face_forward(si.ns, ng);
    if (mat.alpha > 0.0f) {
      // Rough metal: one GGX reflection, its weight G2 / G1 times Turquin's tinted compensation
      // 1 + tint (1 - E) / E (render/material/microfacet.h).
      Vec3 dir;
      float g;
      if (!rough_reflection(ray.direction, si, ng, ns, mat.alpha, depth, dir, g)) return Radiance{};
      const float e = mat.albedo->albedo(dot(-ray.direction, ns));
      const Radiance weight = (tint + tint * tint * ((1.0f - e) / e)) * g;
      const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
      return Radiance(weight *
                      trace(next, depth + 1, self().attenuate(beta, weight, path), medium, path));
    }
    const Vec3 dir = reflection_direction(ray.direction, ns, ng);
    const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
    const ConeBend bend(*this, [&] {
      return SpreadChange{1.0f, 2.0f * normal_spread(si, ray.direction, dot(ray.direction, ns))};
    });
    return Radiance(tint * trace(next, depth + 1, b, medium, path));
  }

  /// Matte and phong surfaces: ambient, direct light, Phong highlight; for phong also the classic
  /// mirror and transmission terms.
  template <class Throughput, class Path>
  auto diffuse(const Ray& ray, const SurfaceInteraction& si, const Material& mat, int depth,
               const Throughput& beta, std::uint32_t medium, const Path& path) {
    using Radiance = typename Derived::Radiance;
    const Vec3& d = ray.direction;
    const Vec3 ng = face_forward(si.ng, -d);
    const Vec3 ns = bumped_normal(mat.texture, si, face_forward(si.ns, ng), ng);
    const Radiance albedo = self().reflectance(texture_colour(mat.texture, si, d), path);
    Radiance result = albedo * self().ambient(path) * mat.ka;
    add_direct_light(result, si, ng, ns, d, albedo, mat, depth, medium, path);
    // Caustic irradiance E: the light that reached this point through dielectrics, which the
    // shadow rays above do not see (they stop at dielectrics), in the units of direct light;
    // spectral scenes uplift it as a light's colour (docs/render.md "Caustics").
    if (m_caustics) {
      const Rgb e = m_caustics->irradiance(si.p, ng);
      if (!e.is_black()) result += albedo * self().illuminant(e, path) * mat.kd;
    }
    // The environment's irradiance ([environment] light_surfaces; environment_lighting.h): its
    // sphere-light caps taken out, opaque occluders found by rays, reflected by the Lambertian
    // BRDF albedo / pi (a white floor in a uniform surround of radiance L shows L: the furnace).
    if (m_environment_occluders) {
      const Rgb e = environment_irradiance(m_scene, *m_environment_occluders, si.p, si.p_error, ng,
                                           ns, si.object, depth, m_camera_sample, m_rays);
      if (!e.is_black())
        result += albedo * self().illuminant(e, path) * (mat.kd * std::numbers::inv_pi_v<float>);
    }
    if (mat.kind != Material::Kind::phong || depth >= m_max_depth) return result;
    if (mat.reflectance > 0.0f && mat.alpha > 0.0f &&
        self().weight(beta, path) * mat.reflectance >= m_min_weight) {
      // Glossy: the mirror term through a GGX lobe, compensated as a conductor of reflectance
      // F0 = reflectance (Turquin 2019).
      Vec3 dir;
      float g;
      if (rough_reflection(d, si, ng, ns, mat.alpha, depth, dir, g)) {
        const float k =
            mat.reflectance * g * mat.albedo->conductor_compensation(dot(-d, ns), mat.reflectance);
        const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
        result += trace(next, depth + 1, beta * k, medium, path) * k;
      }
    } else if (mat.reflectance > 0.0f &&
               self().weight(beta, path) * mat.reflectance >= m_min_weight) {
      const Vec3 dir = reflection_direction(d, ns, ng);
      const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
      result += trace(next, depth + 1, beta * mat.reflectance, medium, path) * mat.reflectance;
    }
    if (mat.transmittance > 0.0f && self().weight(beta, path) * mat.transmittance >= m_min_weight) {
      // The classic model: ior relative to the front side; the carried medium is not changed.
      const bool entering = dot(d, si.ng) < 0.0f;
      const float eta = entering ? mat.ior : 1.0f / mat.ior;
      Vec3 dir;
      if (refract(d, ns, eta, dir) && dot(dir, ng) < 0.0f) {
        const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
        result +=
            trace(next, depth + 1, beta * mat.transmittance, medium, path) * mat.transmittance;
      }
    }
    return result;
  }

  /// The camera sample's sampler (pixel (0, 0) outside a render).
  const sampling::PixelSampler& camera_sampler() const {
    static const sampling::PixelSampler fallback(0, 0);
    return m_camera_sample.sampler ? *m_camera_sample.sampler : fallback;
  }

  /// A scattering event at distance t along `ray` in `medium` (volumetric path tracing, one path
  /// per event: render/media/scattering.h, render/integrator/phase_function.h): a new direction
  /// from the Henyey-Greenstein phase, drawn from the camera sample's pair for this level, the
  /// segment's Beer-Lambert absorption, and the radiance arriving from there. Each event uses one
  /// tree level. No next-event estimation: the light reaches the event along the traced path
  /// (through the interfaces, refracted as everywhere else) or not at all.
  template <class Throughput, class Path>
  auto scatter(const Ray& ray, float t, int depth, const Throughput& beta, std::uint32_t medium,
               const Path& path) {
    using Radiance = typename Derived::Radiance;
    if (depth >= m_max_depth) return Radiance{};
    const sampling::Point2 u = camera_sampler().get_2d(m_camera_sample.sample_index,
                                                       kScatteringDimension + std::uint32_t(depth));
    const Vec3 dir = scatter_henyey_greenstein(ray.direction, m_asymmetry[medium], u.x, u.y);
    Throughput b = beta;
    Radiance segment{};
    bool absorbs = false;
    if constexpr (Derived::kAbsorption) {
      absorbs = self().absorbs(medium);
      if (absorbs) {
        segment = self().transmittance(medium, t, path);
        b = self().attenuate(b, segment, path);
      }
    }
    const Vec3 p = ray.origin + ray.direction * t;
    Radiance l = scatter_direct_light(p, ray.direction, dir, depth, medium, path);
    {
      const AfterScatter mark(*this, true);
      const bool was_scattered = m_path_scattered;
      m_path_scattered = true;
      l += trace(Ray{p, dir}, depth + 1, b, medium, path);
      m_path_scattered = was_scattered;
    }
    if constexpr (Derived::kAbsorption) {
      if (absorbs) l *= segment;
    }
    return l;
  }

  /// Sets whether the rays traced are on a path from a scattering event (sphere lights met
  /// directly, through dielectric interfaces only, are then not counted), for as long as this
  /// object lives.
  class AfterScatter {
   public:
    AfterScatter(WhittedShading& shading, bool value)
        : m_shading(shading), m_saved(shading.m_after_scatter) {
      shading.m_after_scatter = value;
    }
    ~AfterScatter() { m_shading.m_after_scatter = m_saved; }
    AfterScatter(const AfterScatter&) = delete;
    AfterScatter& operator=(const AfterScatter&) = delete;

   private:
    WhittedShading& m_shading;
    bool m_saved;
  };

  /// Next-event estimation at a scattering event at p (ray direction d, in `medium`, tree level
  /// depth): the light scattered towards the viewer, p(cos) L T / pdf (docs/render.md
  /// "Scattering media"). Every light reaches p by one approximation: its shadow ray runs
  /// straight through the dielectric interfaces between them, each crossing transmitting
  /// 1 - R(cos) as seen from p's side (none where p's side reflects totally), each segment its
  /// Beer-Lambert absorption and exp(-sigma_s s). This is exact where the interfaces are
  /// index-matched; where they refract, the light is seen in its unbent direction (a soft box
  /// seen through the ice's surface appears in the glow a little off its true place, the
  /// focusing of the curved surface, a caustic inside the ice, is left out). The path leaving
  /// the event does not count the environment or a sphere light it reaches through
  /// transmissions alone (AfterScatter), the same light these samples bring; after an internal
  /// reflection it counts them again. Under a uniform environment this is exact (the furnace).
  /// - Point lights: one shadow ray each; the phase for the light's direction refracted where
  ///   the shadow ray crosses the first interface.
  /// - Sphere lights: one sample each from the camera sample's pair for this level and light,
  ///   uniform in the light's cone; the phase as for point lights.
  /// - The environment: one direction drawn by its radiance (EnvironmentSampler) and `phase_dir`
  ///   (where the path continues, drawn from the phase), combined by multiple importance
  ///   sampling (Veach 1997, the power heuristic).
  template <class Path>
  auto scatter_direct_light(const Vec3& p, const Vec3& d, const Vec3& phase_dir, int depth,
                            std::uint32_t medium, const Path& path) {
    using Radiance = typename Derived::Radiance;
    Radiance result{};
    const float g = m_asymmetry[medium];
    const auto& lights = m_scene.lights();
    for (std::size_t i = 0; i < lights.size(); ++i) {
      const PointLight& light = lights[i];
      const Vec3 to_light = light.position - p;
      const float dist2 = dot(to_light, to_light);
      if (!(dist2 > 0.0f)) continue;
      const float dist = std::sqrt(dist2);
      const auto walk = shadow_walk(p, to_light / dist, dist * (1.0f - 1e-4f), medium, path);
      if (!walk.open) continue;
      Radiance li = self().light_radiance(i, path);
      if (light.inverse_square) li *= 1.0f / dist2;
      result += walk.apply(*this, li, path) * henyey_greenstein(dot(walk.travel, -d), g);
    }
    const auto& spheres = m_scene.sphere_lights();
    const sampling::PixelSampler& sampler = camera_sampler();
    for (std::size_t k = 0; k < spheres.size(); ++k) {
      const SphereLight& light = spheres[k];
      const sampling::Point2 u = sampler.get_2d(
          m_camera_sample.sample_index,
          kScatteringLightDimension + std::uint32_t(depth) * 64u + std::uint32_t(k % 63u));
      SphereLightSample s;
      if (!sample_sphere_light(light, p, u, s) || !(s.pdf > 0.0f)) continue;
      const auto walk = shadow_walk(p, s.wi, s.distance * (1.0f - 1e-4f), medium, path);
      if (!walk.open) continue;
      Radiance li = self().emission(light.material, path) * (s.falloff_scale / s.pdf);
      result += walk.apply(*this, li, path) * henyey_greenstein(dot(walk.travel, -d), g);
    }
    if (m_environment_sampler) {
      const EnvironmentSampler& env = *m_environment_sampler;
      const auto power = [](float a, float b) { return a * a / (a * a + b * b); };
      constexpr float kOpen = std::numeric_limits<float>::infinity();
      const sampling::Point2 u =
          sampler.get_2d(m_camera_sample.sample_index,
                         kScatteringLightDimension + std::uint32_t(depth) * 64u + 63u);
      float pdf_env = 0.0f;
      const Vec3 w = env.sample(u, pdf_env);
      if (pdf_env > 0.0f) {
        const auto walk = shadow_walk(p, w, kOpen, medium, path);
        if (walk.open) {
          const float pdf_phase = henyey_greenstein(dot(w, d), g);
          result += walk.apply(*this, self().illuminant(background(walk.exit), path), path) *
                    (pdf_phase / pdf_env * power(pdf_env, pdf_phase));
        }
      }
      const auto walk = shadow_walk(p, phase_dir, kOpen, medium, path);
      if (walk.open)
        result += walk.apply(*this, self().illuminant(background(walk.exit), path), path) *
                  power(henyey_greenstein(dot(phase_dir, d), g), env.pdf(phase_dir));
    }
    return result;
  }

  /// What a shadow walk from a scattering event found (shadow_walk()).
  template <class Reflectance>
  struct ShadowWalk {
    /// it reached the light (or left the scene)
    bool open = false;
    /// the light's direction of travel at the event; the walk's last direction
    Vec3 travel, exit;
    /// product of the crossings' transmissions and of exp(-sigma_s s) over the segments
    Reflectance transmission{1.0f};
    float unscattered = 1.0f;
    /// the segments in absorbing media: medium and length
    int segments = 0;
    std::array<std::uint32_t, kMaxShadowCrossings + 1> segment_medium{};
    std::array<float, kMaxShadowCrossings + 1> segment_length{};

    /// Light l after the walk.
    template <class Radiance, class Shading, class Path>
    Radiance apply(Shading& shading, Radiance l, const Path& path) const {
      l = l * transmission * unscattered;
      if constexpr (Derived::kAbsorption) {
        for (int i = 0; i < segments; ++i)
          l *= shading.self().transmittance(segment_medium[i], segment_length[i], path);
      }
      return l;
    }
  };

  /// Follows the light's way back from p along unit direction w in `medium` for a distance
  /// t_max (infinite: out of the scene), straight on through dielectric interfaces (the
  /// approximation of scatter_direct_light()), transmitting 1 - R at each as seen from p's side
  /// (so the light that total internal reflection keeps from p's direction is blocked: the
  /// leaving path brings it), blocked by an opaque surface or too many crossings.
  template <class Path>
  auto shadow_walk(const Vec3& p, const Vec3& w, float t_max, std::uint32_t medium,
                   const Path& path) {
    ShadowWalk<typename Derived::Reflectance> walk;
    walk.travel = -w;
    bool first = true;
    Vec3 origin = p;
    for (int crossing = 0; crossing <= kMaxShadowCrossings; ++crossing) {
      ++m_rays;
      Hit hit;
      const Ray ray{origin, w, t_max};
      const bool found = m_scene.intersect(ray, hit);
      const float s = found ? hit.t : t_max;
      if (m_scattering_per_m[medium] > 0.0f)
        walk.unscattered *= std::exp(-m_scattering_per_m[medium] * s);
      if constexpr (Derived::kAbsorption) {
        if (self().absorbs(medium)) {
          walk.segment_medium[std::size_t(walk.segments)] = medium;
          walk.segment_length[std::size_t(walk.segments++)] = std::min(s, 1e30f);
        }
      }
      if (!found) {
        walk.exit = w;
        walk.open = true;
        return walk;
      }
      const SurfaceInteraction si = m_scene.interaction(ray, hit);
      const SceneObject& obj = m_scene.objects()[si.object];
      if (!obj.dielectric) return walk;
      const FacingInterface fi = facing_interface(w, si, obj);
      if (fi.from != medium) return walk;
      if (!obj.index_matched) {
        const float cos_i = -dot(w, fi.ns);
        const auto f = self().fresnel(fi.from, fi.to, cos_i, path);
        walk.transmission = walk.transmission * (decltype(f.r)(1.0f) - f.r);
        if (is_black(walk.transmission)) return walk;  // total internal reflection
        if (first) {
          // The light comes in from fi.to: its direction after refracting here.
          Vec3 in;
          if (refract(-w, -fi.ns, 1.0f / f.eta, in)) walk.travel = in;
          first = false;
        }
      }
      medium = fi.to;
      origin = offset_ray_origin(si.p, si.p_error, fi.ng, w);
      t_max -= hit.t;
      if (!(t_max > 0.0f)) {
        walk.open = true;
        return walk;
      }
    }
    return walk;
  }

  /// The camera sample's point for the microfacet normal of a rough event at tree level
  /// `depth`: its own dimension pair per level, so that each pixel's samples stratify the normals
  /// of its first rough hits (every event at one level shares the pair: each is unbiased).
  sampling::Point2 microfacet_point(int depth) const {
    const sampling::PixelSampler fallback(0, 0);
    const sampling::PixelSampler& sampler =
        m_camera_sample.sampler ? *m_camera_sample.sampler : fallback;
    return sampler.get_2d(m_camera_sample.sample_index,
                          kMicrofacetDimension + static_cast<std::uint32_t>(depth));
  }

  /// A GGX reflection about a visible normal (render/material/microfacet.h) of the surface with
  /// normals ng, ns facing the viewer: its direction and weight G2 / G1. False when the
  /// reflection leaves below the surface (the light lost to the compensation's table).
  bool rough_reflection(const Vec3& d, const SurfaceInteraction&, const Vec3& ng, const Vec3& ns,
                        float alpha, int depth, Vec3& dir, float& weight) const {
    const microfacet::Frame frame(ns);
    const Vec3 wo = frame.to_local(-d);
    const sampling::Point2 u = microfacet_point(depth);
    Vec3 wi;
    if (!microfacet::conductor_sample(wo, alpha, u.x, u.y, wi, weight)) return false;
    dir = normalize(frame.to_world(wi));
    return dot(dir, ng) > 0.0f;
  }

  /// A rough dielectric interface (Walter et al. 2007): one visible normal m per camera sample
  /// and level, both branches followed as at a smooth interface, each weighed by its Fresnel
  /// factor at m times G2 / G1 and by the compensation 1 / E(mu_o) of the side the ray comes from
  /// (render/material/microfacet.h). Dispersive transmissions are handed to the spectral tracer
  /// with m as the normal (their G2 from the hero wavelength's direction).
  template <class Throughput, class Path>
  auto rough_dielectric(const Ray& ray, const SurfaceInteraction& si, const SceneObject& obj,
                        const FacingInterface& fi, int depth, const Throughput& beta,
                        const Path& path) {
    using Radiance = typename Derived::Radiance;
    using Reflectance = typename Derived::Reflectance;
    const Vec3& d = ray.direction;
    Radiance result{};
    const microfacet::Frame frame(fi.ns);
    const Vec3 wo = frame.to_local(-d);
    const sampling::Point2 u = microfacet_point(depth);
    const Vec3 m_local = microfacet::sample_visible_normal(wo, obj.alpha, u.x, u.y);
    const float cos_m = dot(wo, m_local);
    if (!(cos_m > 0.0f)) return result;
    const Vec3 m = normalize(frame.to_world(m_local));
    const bool entering = fi.from == obj.outside;
    const float compensation =
        (entering ? obj.albedo_entering : obj.albedo_leaving)->dielectric_compensation(wo.z);
    const float g1 = microfacet::ggx_g1(wo, obj.alpha);
    const auto f = self().fresnel(fi.from, fi.to, cos_m, path);
    // Reflected branch.
    {
      const Vec3 wr = m_local * (2.0f * cos_m) - wo;
      const Vec3 dir = normalize(frame.to_world(wr));
      if (wr.z > 0.0f && dot(dir, fi.ng) > 0.0f && !is_black(f.r)) {
        const float g = microfacet::ggx_g2(wo, wr, obj.alpha) / g1 * compensation;
        const Reflectance r = f.r * g;
        const Throughput br = beta * r;
        if (self().weight(br, path) >= m_min_weight) {
          const Ray next{offset_ray_origin(si.p, si.p_error, fi.ng, dir), dir};
          const AfterScatter reflected(*this, false);
          result += trace(next, depth + 1, br, fi.from, path) * r;
        }
      }
    }
    // Transmitted branch.
    Vec3 wt;
    if (!microfacet::refract_about(wo, m_local, f.eta, wt) || !(wt.z < 0.0f)) return result;
    const Vec3 dir = normalize(frame.to_world(wt));
    if (dot(dir, fi.ng) >= 0.0f) return result;
    const float g = microfacet::ggx_g2(wo, wt, obj.alpha) / g1 * compensation;
    const Reflectance t = Reflectance(1.0f) - f.r;
    if constexpr (Derived::kDispersion) {
      if (f.dispersive) {
        self().dispersive_transmission(result, d, si, FacingInterface{fi.from, fi.to, fi.ng, m},
                                       cos_m, depth, beta * g, t * g, path);
        return result;
      }
    }
    const Reflectance tg = t * g;
    const Throughput bt = beta * tg;
    if (!is_black(t) && self().weight(bt, path) >= m_min_weight) {
      const Ray next{offset_ray_origin(si.p, si.p_error, fi.ng, dir), dir};
      result += trace(next, depth + 1, bt, fi.to, path) * tg;
    }
    return result;
  }

  /// A texture's colour at a hit seen along unit direction d: its mean over the tighter box (the
  /// texture's axes or the plane's diagonals) bounding the ray cone's footprint
  /// (Texture::eval_footprint, closed-form lookups), an ellipse of minor
  /// half-axis w and major half-axis w / cos along d's projection on the surface, w the cone's
  /// width at the hit (one pixel there, or what reflections and refractions made of it). Half-axes
  /// of one pixel, a footprint two pixels across: a box average's first zero falls on a checker
  /// whose period is two pixels (cells of one pixel: the Nyquist limit of the pixel grid), so
  /// checks fade to the mean colour where they shrink below a pixel instead of aliasing into
  /// staircases and specks that the few samples of a flat-looking pixel cannot resolve.
  /// Point-sampled without a cone.
  Rgb texture_colour(const Texture& texture, const SurfaceInteraction& si, const Vec3& d) const {
    if (texture.kind == Texture::Kind::solid || m_cone.width == 0.0f) return texture.eval(si.p);
    const float minor = std::abs(m_cone.width);
    const float cos_t = std::max(std::abs(dot(d, si.ng)), 1e-3f);
    Vec3 along = d - si.ng * dot(d, si.ng);
    const float len = length(along);
    // Head-on: any direction in the plane (the footprint is a circle).
    along = len > 1e-6f
                ? along / len
                : normalize(cross(si.ng, std::abs(si.ng.x) < 0.9f ? Vec3{1.0f, 0.0f, 0.0f}
                                                                  : Vec3{0.0f, 1.0f, 0.0f}));
    return texture.eval_footprint(
        TextureFootprint{si.p, along, cross(si.ng, along), minor / cos_t, minor});
  }

  /// The shading normal ns (facing the viewer, geometric normal ng) tilted by a noise texture's
  /// bump (Blinn 1978): the height h = bump_m * value is differentiated by forward differences
  /// along two tangents over a step of the cone's footprint width (the filtered field's own
  /// scale; 1e-3 of the feature size without a cone), n = normalize(ns - grad h). Unchanged
  /// where there is no bump or the tilted normal would face away from ng.
  Vec3 bumped_normal(const Texture& texture, const SurfaceInteraction& si, const Vec3& ns,
                     const Vec3& ng) const {
    if (texture.kind != Texture::Kind::noise || texture.bump_m <= 0.0f) return ns;
    const float w = std::max(std::abs(m_cone.width), 1e-3f * texture.size);
    const microfacet::Frame frame(ns);
    const Vec3 t1 = frame.to_world(Vec3{1.0f, 0.0f, 0.0f}),
               t2 = frame.to_world(Vec3{0.0f, 1.0f, 0.0f});
    const float h0 = texture.noise_value(si.p, w);
    const float k = texture.bump_m / w;
    const float g1 = k * (texture.noise_value(si.p + t1 * w, w) - h0),
                g2 = k * (texture.noise_value(si.p + t2 * w, w) - h0);
    const Vec3 n = normalize(ns - t1 * g1 - t2 * g2);
    return dot(n, ng) > 0.0f ? n : ns;
  }

  /// How much the surface normal turns across the cone's footprint at a hit [rad], signed:
  /// curvature times the footprint's length along the surface, |w| / cos (Ray Tracing Gems
  /// ch. 20's surface spread angle); positive where the surface is convex towards the ray d
  /// (closed surfaces have outward geometric normals), negative where concave.
  float normal_spread(const SurfaceInteraction& si, const Vec3& d, float cos_i) const {
    const float convex = dot(d, si.ng) < 0.0f ? 1.0f : -1.0f;
    return convex * si.curvature * std::abs(m_cone.width) / std::max(std::abs(cos_i), 1e-3f);
  }

  /// How a curved specular hit changes the cone's spread: spread' = spread * scale + bend.
  struct SpreadChange {
    float scale, bend;
  };

  /// The ray cone of the rays leaving a curved specular hit, for as long as this object lives:
  /// spread' = spread * scale + bend, signed (a focusing cone's width passes through 0 and
  /// changes sign; the footprint uses |width|), within +-1 rad. `change()` gives the
  /// SpreadChange; it is evaluated only while there is a cone (never at 1 sample per pixel, where
  /// textures are point-sampled: its divisions would be wasted on every mirror and glass hit).
  class ConeBend {
   public:
    template <class Change>
    ConeBend(WhittedShading& shading, Change&& change)
        : m_shading(shading), m_saved(shading.m_cone.spread) {
      if (shading.m_cone.width != 0.0f || m_saved != 0.0f) {
        const SpreadChange c = change();
        shading.m_cone.spread = std::clamp(m_saved * c.scale + c.bend, -1.0f, 1.0f);
      }
    }
    ~ConeBend() { m_shading.m_cone.spread = m_saved; }
    ConeBend(const ConeBend&) = delete;
    ConeBend& operator=(const ConeBend&) = delete;

   private:
    WhittedShading& m_shading;
    float m_saved;
  };

  /// Direct light at a diffuse hit (normals ng, ns facing the viewer, unit view direction d, tree
  /// level depth): adds albedo L kd cos + the Phong highlight of every light seen to `result`
  /// (accumulated in place, light by light). All lights of the scene are handled here. Shadow
  /// rays stop at every dielectric that is not index-matched, for point and sphere lights alike:
  /// the light that passes through dielectrics is the caustic term, which the photon map
  /// (traced from both kinds of light) supplies in diffuse(); nothing is counted twice.
  /// A hit reached in `medium` sees no light in another medium: its shadow rays (which stop at
  /// every dielectric that is not index-matched) would all end at the interface between the two,
  /// so they are not cast (the floor under the default film's puddle: 4 shadow rays per hit, all
  /// blocked by the water's surface; the result is the same).
  template <class Radiance, class Path>
  void add_direct_light(Radiance& result, const SurfaceInteraction& si, const Vec3& ng,
                        const Vec3& ns, const Vec3& d, const Radiance& albedo, const Material& mat,
                        int depth, std::uint32_t medium, const Path& path) {
    const auto reaches = [&](std::uint32_t light_medium) {
      return light_medium == medium || !m_interfaces_stop_shadow_rays;
    };
    const auto& lights = m_scene.lights();
    for (std::size_t i = 0; i < lights.size(); ++i) {
      if (!reaches(m_point_light_medium[i])) continue;
      const PointLight& light = lights[i];
      Vec3 l;
      float cos_l, dist2;
      if (light_visibility(si.p, si.p_error, ng, ns, light, l, cos_l, dist2) !=
          LightVisibility::seen)
        continue;
      Radiance li = self().light_radiance(i, path);
      if (light.inverse_square) li *= 1.0f / dist2;
      result += albedo * li * (mat.kd * cos_l);
      if (mat.ks > 0.0f) {
        const float s = dot(reflect(-l, ns), -d);
        if (s > 0.0f) result += li * (mat.ks * std::pow(s, mat.shininess));
      }
    }
    if (std::none_of(m_sphere_light_medium.begin(), m_sphere_light_medium.end(), reaches)) return;
    // Sphere lights (render/light/light_sampling.h): the exact unoccluded irradiance times the
    // visible share of the camera sample's stratified shadow samples; the highlight per sample.
    const auto& spheres = m_scene.sphere_lights();
    const sampling::PixelSampler fallback(0, 0);
    const CameraSampleContext camera =
        m_camera_sample.sampler ? m_camera_sample : CameraSampleContext{&fallback, 0};
    sample_sphere_lights(
        m_scene, si.p, si.p_error, ng, ns, depth, camera, m_rays,
        [&](std::size_t k, float e) {
          result += albedo * self().emission(spheres[k].material, path) * (mat.kd * e);
        },
        [&](std::size_t k, const Vec3& wi, float weight) {
          if (mat.ks <= 0.0f) return;
          const float s = dot(reflect(-wi, ns), -d);
          if (s > 0.0f)
            result += self().emission(spheres[k].material, path) *
                      (weight * mat.ks * std::pow(s, mat.shininess));
        },
        mat.ks > 0.0f);
  }

  const Scene& m_scene;
  const photon::CausticMap* m_caustics;
  /// what may hide the environment from diffuse surfaces (only with light_surfaces)
  std::optional<EnvironmentOccluders> m_environment_occluders;
  int m_max_depth;
  float m_min_weight;
  std::uint64_t m_rays = 0, m_mismatches = 0;
  /// no object is index-matched: every dielectric interface stops shadow rays
  bool m_interfaces_stop_shadow_rays = true;
  /// per medium: scattering coefficient [1/m] and Henyey-Greenstein g (render/media/scattering.h)
  std::vector<float> m_scattering_per_m, m_asymmetry;
  bool m_any_scattering = false;
  /// the rays being traced continue a path from a scattering event through transmissions alone
  /// (AfterScatter): the environment and sphere lights they reach are not counted
  bool m_after_scatter = false;
  /// the rays being traced continue a path that has scattered: free paths are sampled, not split
  bool m_path_scattered = false;
  /// per material: the emissive material of a sphere light's visible sphere
  std::vector<bool> m_light_material;
  /// importance sampling of the environment for scattering events (scenes that scatter and whose
  /// environment is not black)
  std::shared_ptr<const EnvironmentSampler> m_environment_sampler;
  /// the medium each point light and sphere light is in (photon::medium_at)
  std::vector<std::uint32_t> m_point_light_medium, m_sphere_light_medium;
  /// the camera sample being traced (set_camera_sample()); no sampler: pixel (0, 0), sample 0
  CameraSampleContext m_camera_sample{};
  /// A ray cone (Amanatides 1984; Akenine-Moeller et al. 2019, Ray Tracing Gems ch. 20): width
  /// [scene units] at the current ray's origin and spread angle [rad].
  struct RayCone {
    float width = 0, spread = 0;
  };
  float m_pixel_spread = 0;
  float m_haze_distance = 0;
  RayCone m_cone{};
};

}  // namespace thaw::render
