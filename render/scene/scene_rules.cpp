#include "render/scene/scene_rules.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "render/scene/caustic_keys.h"
#include "render/scene/image_keys.h"

namespace thaw::render {
namespace {

/// Shortest text that reads back as the same double, as %g would lay it out ("0.0001", "1e+30").
std::string num(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general);
  return std::string(buf, r.ptr);
}

std::optional<std::string> int_between(long long v, long long lo, long long hi) {
  if (v >= lo && v <= hi) return std::nullopt;
  return "must be between " + std::to_string(lo) + " and " + std::to_string(hi) + " (got " +
         std::to_string(v) + ")";
}

/// [lo, hi] with the unit after the bounds ("between 0.05 and 100 nm (got 0)").
std::optional<std::string> real_between(double v, double lo, double hi, const std::string& unit) {
  if (v >= lo && v <= hi) return std::nullopt;  // false for NaN
  return "must be between " + num(lo) + " and " + num(hi) + unit + " (got " + num(v) + ")";
}

double length3(const Vec3d& v) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}
bool finite3(const Vec3d& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}
double max_abs(const Vec3d& v) {
  return std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])});
}

/// Every [image] row's rule (render/scene/image_keys.h), then the image's pixel count.
std::optional<SceneProblem> image_problem(const ImageSettings& img) {
  for (const ImageKey& key : image_keys())
    if (auto problem = key_problem(key, img))
      return SceneProblem{"image." + std::string(key.name), *problem};
  if (auto problem = image_pixels_problem(img.width, img.height))
    return SceneProblem{"image.height", *problem};
  return std::nullopt;
}

}  // namespace

std::optional<ImageSettings::Dispersion> dispersion_from_name(std::string_view name) {
  if (name == "adaptive") return ImageSettings::Dispersion::adaptive;
  if (name == "split") return ImageSettings::Dispersion::split;
  if (name == "hero") return ImageSettings::Dispersion::hero;
  return std::nullopt;
}

std::optional<ImageSettings::WavelengthPattern> wavelength_pattern_from_name(
    std::string_view name) {
  if (name == "shared") return ImageSettings::WavelengthPattern::shared;
  if (name == "per_pixel") return ImageSettings::WavelengthPattern::per_pixel;
  return std::nullopt;
}

std::optional<std::string> image_side_problem(long long pixels) {
  return int_between(pixels, 1, kMaxImageSide);
}

std::optional<std::string> image_pixels_problem(long long width, long long height) {
  if (width * height <= kMaxImagePixels) return std::nullopt;  // sides are <= 2^14 by now
  return "the image has too many pixels (" + std::to_string(width) + "x" + std::to_string(height) +
         "; the limit is " + std::to_string(kMaxImagePixels) + ")";
}

std::optional<std::string> samples_per_pixel_problem(long long samples) {
  return int_between(samples, 1, kMaxSamplesPerPixel);
}

std::optional<std::string> min_samples_problem(long long samples) {
  // At least two samples, for a standard error; more than the cap is the cap.
  return int_between(samples, 2, kMaxSamplesPerPixel);
}

std::optional<std::string> adaptive_threshold_problem(double threshold) {
  return real_between(threshold, kMinAdaptiveThreshold, kMaxAdaptiveThreshold, " display units");
}

std::optional<std::string> filter_radius_problem(double radius_px) {
  return real_between(radius_px, kMinFilterRadius, kMaxFilterRadius, " pixels");
}

std::optional<std::string> max_depth_problem(long long depth) {
  return int_between(depth, 1, kMaxDepth);
}

std::optional<std::string> min_weight_problem(double weight) {
  if (weight >= 0.0 && std::isfinite(weight)) return std::nullopt;
  return "must be a finite number >= 0 (got " + num(weight) + ")";
}

std::optional<std::string> dispersion_wavelengths_problem(long long count) {
  return int_between(count, kMinDispersionWavelengths, kMaxDispersionWavelengths);
}

std::optional<std::string> dispersion_resolution_problem(double resolution_nm) {
  return real_between(resolution_nm, kMinDispersionResolutionNm, kMaxDispersionResolutionNm, " nm");
}

std::optional<std::string> exposure_problem(double stops) {
  return real_between(stops, -kMaxExposureStops, kMaxExposureStops, " stops");
}

std::optional<std::string> dispersion_name_problem(std::string_view name) {
  if (dispersion_from_name(name)) return std::nullopt;
  return "must be \"adaptive\", \"split\" or \"hero\" (got \"" + std::string(name) + "\")";
}

std::optional<std::string> wavelength_pattern_name_problem(std::string_view name) {
  if (wavelength_pattern_from_name(name)) return std::nullopt;
  return "must be \"shared\" or \"per_pixel\" (got \"" + std::string(name) + "\")";
}

std::optional<std::string> vertical_fov_problem(double degrees) {
  if (degrees >= kMinFovDeg && degrees < 180.0) return std::nullopt;
  return "must be in [" + num(kMinFovDeg) + ", 180) degrees (got " + num(degrees) + ")";
}

std::optional<std::string> light_radius_problem(double radius) {
  // A float radius: the light is a sphere primitive in single precision.
  if (radius > 0.0 && std::isfinite(static_cast<float>(radius))) return std::nullopt;
  return "a sphere light needs a positive radius (got " + num(radius) + ")";
}

std::optional<std::string> light_intensity_problem(double intensity) {
  if (intensity >= 0.0) return std::nullopt;  // infinity: light_problem's
  return "must not be negative (got " + num(intensity) + ")";
}

std::optional<std::string> light_samples_problem(long long samples) {
  return int_between(samples, 1, kMaxLightSamples);
}

std::optional<std::string> ior_problem(double ior) {
  if (ior >= kMinIor && ior < kMaxIor) return std::nullopt;
  return "must be in [" + num(kMinIor) + ", " + num(kMaxIor) + ") (got " + num(ior) + ")";
}

std::optional<std::string> roughness_problem(double roughness) {
  return real_between(roughness, 0.0, 1.0, "");
}

std::optional<std::string> caustic_photons_problem(long long photons) {
  if (photons >= kMinCausticPhotons && photons <= kMaxCausticPhotons) return std::nullopt;
  return "must be between " + std::to_string(kMinCausticPhotons) + " and 1e7 (got " +
         std::to_string(photons) + "); each takes about 200 bytes of memory";
}

std::optional<std::string> caustic_radius_problem(double radius) {
  return real_between(radius, kMinCausticRadius, kMaxCausticRadius, " scene units");
}

std::optional<std::string> environment_intensity_problem(double intensity) {
  return real_between(intensity, 0.0, 1e6, "");
}

std::optional<std::string> environment_exponent_problem(double exponent) {
  if (exponent > 0.0 && exponent <= 10.0) return std::nullopt;
  return "must be in (0, 10] (got " + num(exponent) + ")";
}

std::optional<std::string> environment_rotation_problem(double degrees) {
  return real_between(degrees, -360.0, 360.0, " degrees");
}

std::optional<std::string> environment_samples_problem(long long samples) {
  return int_between(samples, 1, kMaxLightSamples);
}

std::optional<std::string> environment_haze_problem(double distance) {
  return real_between(distance, 0.0, 1e9, "");
}

std::optional<std::string> panel_size_problem(double degrees) {
  if (degrees > 0.0 && degrees < 170.0) return std::nullopt;
  return "must be in (0, 170) degrees (got " + num(degrees) + ")";
}

std::optional<std::string> panel_edge_problem(double degrees) {
  return real_between(degrees, 0.0, 30.0, " degrees");
}

std::optional<std::string> placement_problem(double reach, double detail) {
  // Spacing of floats at `reach`: 2^(e - 23) for reach in [2^e, 2^(e+1)) (24-bit significand),
  // so every reach below detail / kMinResolvedParts * 2^23 passes.
  const float f = static_cast<float>(std::abs(reach));
  const double spacing = std::isfinite(f)
                             ? double(std::nextafter(f, std::numeric_limits<float>::infinity())) - f
                             : std::numeric_limits<double>::infinity();
  if (spacing * kMinResolvedParts <= detail) return std::nullopt;
  return "reaches " + num(reach) + " from the origin, where single precision (the renderer's) " +
         "resolves only steps of " + num(spacing) + ", too coarse for details of " + num(detail) +
         "; keep the object within " + num(detail / kMinResolvedParts * 8388608.0) +
         " of the origin";
}

std::optional<SceneProblem> camera_problem(const CameraDescription& cam) {
  const std::string within = "must be finite and within " + num(kMaxCoordinate) + " of the origin";
  if (!finite3(cam.position) || max_abs(cam.position) > kMaxCoordinate)
    return SceneProblem{"position", within};
  if (!finite3(cam.look_at) || max_abs(cam.look_at) > kMaxCoordinate)
    return SceneProblem{"look_at", within};
  if (!finite3(cam.up) || length3(cam.up) == 0.0)
    return SceneProblem{"up", "must be a finite, non-zero vector"};
  if (auto p = vertical_fov_problem(cam.vertical_fov_deg))
    return SceneProblem{"vertical_fov_deg", *p};
  const Vec3d d{cam.look_at[0] - cam.position[0], cam.look_at[1] - cam.position[1],
                cam.look_at[2] - cam.position[2]};
  if (length3(d) == 0.0) return SceneProblem{"look_at", "must differ from the camera position"};
  const Vec3d c{d[1] * cam.up[2] - d[2] * cam.up[1], d[2] * cam.up[0] - d[0] * cam.up[2],
                d[0] * cam.up[1] - d[1] * cam.up[0]};
  if (length3(c) <= 1e-9 * length3(d) * length3(cam.up))
    return SceneProblem{"up", "must not be parallel to the viewing direction"};
  return std::nullopt;
}

std::optional<SceneProblem> light_problem(const LightDescription& l) {
  if (!finite3(l.position)) return SceneProblem{"position", "must be finite"};
  if (!(l.intensity >= 0.0) || !std::isfinite(l.intensity))
    return SceneProblem{"intensity", "must be a finite number >= 0 (got " + num(l.intensity) + ")"};
  if (l.kind != LightDescription::Kind::sphere) return std::nullopt;
  if (auto p = light_radius_problem(l.radius)) return SceneProblem{"radius", *p};
  if (auto p = light_samples_problem(l.samples)) return SceneProblem{"samples", *p};
  return std::nullopt;
}

std::optional<SceneProblem> object_problem(const ObjectDescription& o) {
  if (auto p = roughness_problem(o.roughness)) return SceneProblem{"roughness", *p};
  switch (o.shape) {
    case ObjectDescription::Shape::sphere:
      if (!finite3(o.center)) return SceneProblem{"center", "must be finite"};
      if (auto p = real_between(o.radius, kMinObjectSize, kMaxCoordinate, " scene units"))
        return SceneProblem{"radius", *p};
      if (auto p = placement_problem(max_abs(o.center) + o.radius, o.radius))
        return SceneProblem{"center", *p};
      return std::nullopt;
    case ObjectDescription::Shape::box: {
      if (!finite3(o.box_min) || !finite3(o.box_max))
        return SceneProblem{"min", "box corners must be finite"};
      double thinnest = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 3; ++k) {
        if (!(o.box_min[k] < o.box_max[k]))
          return SceneProblem{"max", "must exceed min in every coordinate"};
        thinnest = std::min(thinnest, o.box_max[k] - o.box_min[k]);
      }
      if (auto p = placement_problem(std::max(max_abs(o.box_min), max_abs(o.box_max)), thinnest))
        return SceneProblem{"max", *p};
      return std::nullopt;
    }
    case ObjectDescription::Shape::plane: {
      if (!finite3(o.point)) return SceneProblem{"point", "must be finite"};
      const double len = length3(o.normal);
      if (!finite3(o.normal) || !(std::abs(len - 1.0) <= 1e-6))
        return SceneProblem{"normal", "must be a unit vector (its length is " + num(len) + ")"};
      return std::nullopt;
    }
    case ObjectDescription::Shape::mesh:
      if (!(o.scale > 0.0) || !std::isfinite(o.scale))
        return SceneProblem{"scale", "must be positive and finite (got " + num(o.scale) + ")"};
      // Beyond kMaxCoordinate no mesh can be placed (issue 27: a translate of 1e308 was reported
      // against the OBJ file at build time); refused here, against the scene file's line.
      if (!finite3(o.translate) || max_abs(o.translate) > kMaxCoordinate)
        return SceneProblem{"translate",
                            "must be finite and within " + num(kMaxCoordinate) + " of the origin"};
      if (!finite3(o.rotate_deg) || max_abs(o.rotate_deg) > 360.0)
        return SceneProblem{"rotate_deg", "must be finite, each angle within -360..360 degrees"};
      return std::nullopt;  // placement: build_scene, once the mesh is loaded
  }
  return std::nullopt;
}

std::optional<SceneProblem> find_scene_problem(const SceneDescription& s) {
  if (auto p = image_problem(s.image)) return p;
  for (const CausticKey& key : caustic_keys())  // an automatic value passes
    if (auto p = key_problem(key, s.caustics))
      return SceneProblem{"caustics." + std::string(key.name), *p};
  if (s.environment.kind != EnvironmentDescription::Kind::constant)
    if (auto p = environment_intensity_problem(s.environment.intensity))
      return SceneProblem{"environment.intensity", *p};
  if (s.environment.kind == EnvironmentDescription::Kind::sky)
    if (auto p = environment_exponent_problem(s.environment.exponent))
      return SceneProblem{"environment.exponent", *p};
  if (s.environment.kind == EnvironmentDescription::Kind::latlong)
    if (auto p = environment_rotation_problem(s.environment.rotation_deg))
      return SceneProblem{"environment.rotation_deg", *p};
  if (auto p = environment_samples_problem(s.environment.occlusion_samples))
    return SceneProblem{"environment.occlusion_samples", *p};
  if (auto p = environment_haze_problem(s.environment.haze_distance))
    return SceneProblem{"environment.haze_distance", *p};
  for (std::size_t i = 0; i < s.environment.panels.size(); ++i) {
    const PanelDescription& panel = s.environment.panels[i];
    const std::string key = "environment.panels[" + std::to_string(i) + "].";
    const double len = std::sqrt(panel.direction[0] * panel.direction[0] +
                                 panel.direction[1] * panel.direction[1] +
                                 panel.direction[2] * panel.direction[2]);
    if (!(std::abs(len - 1.0) <= 1e-6))
      return SceneProblem{key + "direction", "must be a unit vector"};
    if (auto p = panel_size_problem(panel.width_deg)) return SceneProblem{key + "width_deg", *p};
    if (auto p = panel_size_problem(panel.height_deg)) return SceneProblem{key + "height_deg", *p};
    if (auto p = panel_edge_problem(panel.edge_deg)) return SceneProblem{key + "edge_deg", *p};
    if (auto p = environment_intensity_problem(panel.intensity))
      return SceneProblem{key + "intensity", *p};
  }
  if (auto p = camera_problem(s.camera)) return SceneProblem{"camera." + p->key, p->problem};
  for (std::size_t i = 0; i < s.lights.size(); ++i)
    if (auto p = light_problem(s.lights[i]))
      return SceneProblem{"lights[" + std::to_string(i) + "]." + p->key, p->problem};
  for (const MediumDescription& m : s.media) {
    // A constant index, bare or in a spec; other models are validated over the spectrum by
    // render/media.
    const bool spec_constant =
        m.spec && m.spec->ior && m.spec->ior->kind() == media::IorModel::Kind::constant;
    if (m.spec && !spec_constant) continue;
    const double n = spec_constant ? m.spec->ior->n_at(media::kFraunhoferD_nm) : m.ior;
    if (auto p = ior_problem(n)) return SceneProblem{"media." + m.name + ".ior", *p};
  }
  for (const MaterialDescription& m : s.materials)
    if (auto p = roughness_problem(m.roughness))
      return SceneProblem{"materials." + m.name + ".roughness", *p};
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    const ObjectDescription& o = s.objects[i];
    if (auto p = object_problem(o)) {
      const std::string label = o.label.empty() ? "objects[" + std::to_string(i) + "]" : o.label;
      return SceneProblem{label + "." + p->key, p->problem};
    }
  }
  return std::nullopt;
}

}  // namespace thaw::render
