#pragma once
// The limits on a scene's values, written once: the scene parser (with the file's line), the CLI
// flags that override [image] keys (`thaw render --width ...`, `thaw run --size/--spp`) and
// build_scene (scenes built in code) all call these, so a bad value gets the same words wherever
// it comes from. Each rule returns the problem ("must be between 1 and 16384 (got 0)") or nullopt.
// Knows nothing of TOML, flags or files: callers add where the value came from.
#include <optional>
#include <string>
#include <string_view>

#include "render/scene/scene_description.h"

namespace thaw::render {

/// Largest accepted image side [pixels] and pixel count.
inline constexpr int kMaxImageSide = 16384;
inline constexpr long long kMaxImagePixels = 1LL << 26;
/// Accepted [image] samples_per_pixel (the cap) and min_samples, [image] adaptive_threshold
/// (display units) and [[lights]] samples of a sphere light.
inline constexpr int kMaxSamplesPerPixel = 65536;
inline constexpr double kMinAdaptiveThreshold = 1e-4, kMaxAdaptiveThreshold = 1.0;
inline constexpr int kMaxLightSamples = 1024;
/// Accepted [image] max_depth (levels of the ray tree; min_weight ends most paths far sooner, and
/// nested-shell furnace tests need about 200).
inline constexpr int kMaxDepth = 256;
/// Accepted [image] dispersion_wavelengths and dispersion_resolution_nm [nm].
inline constexpr int kMinDispersionWavelengths = 4, kMaxDispersionWavelengths = 1024;
inline constexpr double kMinDispersionResolutionNm = 0.05, kMaxDispersionResolutionNm = 100.0;
/// Accepted constant index of refraction of a medium: [1, 10) (no transparent solid exceeds ~4).
inline constexpr double kMinIor = 1.0, kMaxIor = 10.0;
/// Accepted [caustics] photons (a count outside is a mistake, not a quality setting). Memory
/// grows with the count: 1e7 photons took 2.1 GB (peak RSS, a 24x16 test scene whose caustics
/// land on a floor), so 1e9, the old limit, asked for about 200 GB and a typo of 1e9 for 1e6
/// ran out of memory after minutes instead of being refused.
inline constexpr long long kMinCausticPhotons = 1, kMaxCausticPhotons = 10000000LL;
/// Accepted [caustics] radius [scene units]: its square stays a normal single-precision number.
inline constexpr double kMinCausticRadius = 1e-12, kMaxCausticRadius = 1e12;
/// Accepted [camera] vertical_fov_deg: [kMinFovDeg, 180) degrees (below, the pixel footprint
/// underflows single precision; 1e-3 degrees is a 3.6-arcsecond telescope).
inline constexpr double kMinFovDeg = 1e-3;
/// Accepted [image] exposure [stops]: 2^64 still multiplies a pixel to a finite float.
inline constexpr double kMaxExposureStops = 64.0;
/// Largest coordinate of the camera's position and look_at, and smallest and largest size of an
/// analytic object [scene units]: single precision (the renderer's) must hold them and their
/// squares.
inline constexpr double kMaxCoordinate = 1e15, kMinObjectSize = 1e-15;
/// Single precision (the renderer's coordinates) must resolve an object's detail (a mesh's mean
/// edge, a sphere's radius, a box's thinnest side) to at least this many parts: rounding then
/// moves a vertex by at most 1/128 of an edge, so an edge turns by at most about 1/64 rad (facet
/// normals within a degree) and a closed, outward mesh stays closed and outward.
inline constexpr double kMinResolvedParts = 64;

// [image]
std::optional<std::string> image_side_problem(long long pixels);
std::optional<std::string> image_pixels_problem(long long width, long long height);
std::optional<std::string> samples_per_pixel_problem(long long samples);
std::optional<std::string> min_samples_problem(long long samples);
std::optional<std::string> adaptive_threshold_problem(double threshold);
std::optional<std::string> filter_radius_problem(double radius_px);
std::optional<std::string> max_depth_problem(long long depth);
std::optional<std::string> min_weight_problem(double weight);
std::optional<std::string> dispersion_wavelengths_problem(long long count);
std::optional<std::string> dispersion_resolution_problem(double resolution_nm);
std::optional<std::string> exposure_problem(double stops);
/// [image] dispersion and wavelength_pattern values by name, as in scene files and the flags of
/// `thaw render`; nullopt for an unknown name.
std::optional<ImageSettings::Dispersion> dispersion_from_name(std::string_view name);
std::optional<ImageSettings::WavelengthPattern> wavelength_pattern_from_name(std::string_view name);
/// The problem with such a name (the accepted values), or nullopt.
std::optional<std::string> dispersion_name_problem(std::string_view name);
std::optional<std::string> wavelength_pattern_name_problem(std::string_view name);

// [camera], [[lights]], [media], [caustics]
std::optional<std::string> vertical_fov_problem(double degrees);
std::optional<std::string> light_radius_problem(double radius);
std::optional<std::string> light_samples_problem(long long samples);
/// A light's intensity as the file gives it: not negative (NaN included).
std::optional<std::string> light_intensity_problem(double intensity);
std::optional<std::string> ior_problem(double ior);
/// roughness of a dielectric object, a metal or a phong material: [0, 1]
std::optional<std::string> roughness_problem(double roughness);
std::optional<std::string> caustic_photons_problem(long long photons);
std::optional<std::string> caustic_radius_problem(double radius);
// [environment]
/// intensity of a sky or lat-long map: [0, 1e6]
std::optional<std::string> environment_intensity_problem(double intensity);
/// exponent of a sky's gradient: (0, 10]
std::optional<std::string> environment_exponent_problem(double exponent);
/// rotation_deg of a lat-long map: [-360, 360]
std::optional<std::string> environment_rotation_problem(double degrees);
/// occlusion_samples of an environment lighting surfaces: 1..1024
std::optional<std::string> environment_samples_problem(long long samples);
/// haze_distance of an environment: [0, 1e9] scene units (0 = no haze)
std::optional<std::string> environment_haze_problem(double distance);
/// width_deg / height_deg of a sky panel: (0, 170)
std::optional<std::string> panel_size_problem(double degrees);
/// edge_deg of a sky panel: [0, 30]
std::optional<std::string> panel_edge_problem(double degrees);

/// An object with detail `detail` (scene units; see kMinResolvedParts) whose coordinates reach
/// `reach` from the origin: a problem when single precision there is coarser than
/// detail / kMinResolvedParts (a huge translation, e.g. a floor at y = 2^31, collapses a small
/// mesh into a few points, which then fails every later check with a misleading message).
std::optional<std::string> placement_problem(double reach, double detail);

/// A problem and the key it concerns: relative to the table for camera_problem, light_problem and
/// object_problem ("up", "radius"), dotted from the root for find_scene_problem.
struct SceneProblem {
  std::string key, problem;
};
/// [camera]: finite vectors, the field of view, a camera that looks somewhere with an up vector
/// off the viewing direction.
std::optional<SceneProblem> camera_problem(const CameraDescription& camera);
/// One [[lights]] entry: finite position, intensity >= 0, a sphere light's radius and samples.
std::optional<SceneProblem> light_problem(const LightDescription& light);
/// One [[objects]] entry's shape values (sphere radius, box corners, plane normal, mesh scale and
/// translate) and the placement of analytic shapes (placement_problem).
std::optional<SceneProblem> object_problem(const ObjectDescription& object);

/// The problem with a whole description and its dotted key ("image.width", "lights[1].radius",
/// "ball.radius"), or nullopt: every rule above applied to every value, plus what only a whole
/// scene can say (finite coordinates, a camera that looks somewhere). build_scene calls it;
/// mesh files are not read here (build_scene checks their placement once loaded).
std::optional<SceneProblem> find_scene_problem(const SceneDescription& scene);

}  // namespace thaw::render
