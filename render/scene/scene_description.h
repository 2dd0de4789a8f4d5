#pragma once
// What a scene is, as plain data: parsed from TOML by render/format/scene_parser.h or filled in by
// code (the pipeline adds its two shell meshes this way), then turned into a renderable Scene by
// build_scene() (render/scene/scene.h), which validates names and geometry. Double precision,
// scene units (metres for thaw's own scenes), linear RGB. Knows nothing about TOML.
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/film/filter.h"
#include "render/film/view_transform.h"
#include "render/geometry/triangle_mesh.h"
#include "render/media/medium.h"

namespace thaw::render {

using Vec3d = std::array<double, 3>;
using RgbD = std::array<double, 3>;

struct ImageSettings {
  int width = 640;
  int height = 480;
  /// camera samples per pixel; with adaptive = true the cap (render/film/adaptive_pixel.h)
  int samples_per_pixel = 1;
  /// adaptive anti-aliasing: min_samples everywhere, doubled while the pixel's display-space
  /// standard error exceeds adaptive_threshold, up to samples_per_pixel
  bool adaptive = true;
  /// the first batch, >= 2 (one pair); in spectral renders also the wavelength strata (one per
  /// pair) every pixel averages
  int min_samples = 2;
  /// [display units: 1/255 is one 8-bit step]
  double adaptive_threshold = 0.01;
  /// reconstruction filter (render/film/filter.h) and its radius [pixels]
  FilterKind filter = FilterKind::gaussian;
  double filter_radius = 1.5;
  /// textures averaged over each camera sample's ray cone (render/material/texture.h), when
  /// samples_per_pixel > 1; at one sample per pixel everything is point-sampled (POV-Ray)
  bool texture_filter = true;
  /// levels of the Whitted tree, the primary ray being level 1 (POV-Ray max_trace_level)
  int max_depth = 10;
  /// radiance of every ray that escapes the scene (linear RGB)
  RgbD background{0.0, 0.0, 0.0};
  /// branches whose weight falls below this are not traced (POV-Ray adc_bailout, 1/255)
  double min_weight = 1.0 / 255.0;
  /// 2^exposure scales radiance before PNG encoding [stops]
  double exposure = 0.0;
  /// [image] tone: the view transform of PNG outputs (render/film/view_transform.h): agx (the
  /// default: a filmic roll-off, no clipped highlights) or clip (exposed and clamped to [0, 1], as
  /// POV-Ray; the comparison scenes set it). PFM and EXR stay linear either way.
  ViewTransform view = ViewTransform::agx;
  /// spectral transport (render/integrator/spectral_whitted.h): automatic = on iff some medium
  /// is dispersive or absorbs (build_scene decides); off renders RGB with each medium's n_d
  /// and per-channel absorption (media::Absorption::srgb_per_m)
  enum class Spectral { automatic, on, off };
  Spectral spectral = Spectral::automatic;
  /// at a refraction into or out of a dispersive medium: split = one ray per carried wavelength
  /// (4 rays, every wavelength's radiance exact, low colour noise); hero = continue with the hero
  /// wavelength only (terminate_secondary(), one ray, more colour noise)
  /// adaptive = split, and where the throughput up to the refraction is the same at every
  /// wavelength, the transmitted light is integrated over the whole spectrum with its jumps
  /// (fringes) located to within dispersion_resolution_nm: fringes without colour noise
  enum class Dispersion { adaptive, split, hero };
  Dispersion dispersion = Dispersion::adaptive;
  /// adaptive mode: width [nm] to which the wavelength of a fringe's colour jump is located
  double dispersion_resolution_nm = 4.0;
  /// adaptive mode: wavelengths probed across 380-780 nm (spaced by the visible hero density)
  /// to find where the refracted light's colour jumps; more find thinner fringes. split mode:
  /// wavelengths traced per camera sample that meets a dispersive refraction, rounded up to a
  /// multiple of 4 (one packet of 4 per trace of the sample); samples that meet none trace one.
  int dispersion_wavelengths = 10;
  /// which wavelengths the camera samples carry: shared = the same stratified set in every pixel
  /// (one random offset per image, from the seed: a spectral quadrature whose error is smooth
  /// banding across the image and stable from frame to frame, as POV-Ray's dispersion_samples);
  /// per_pixel = drawn independently per pixel (the error is colour speckle instead). Unbiased
  /// over the offset either way.
  enum class WavelengthPattern { shared, per_pixel };
  WavelengthPattern wavelength_pattern = WavelengthPattern::shared;
  /// spectral film: ratio = each pixel's XYZ is divided, channel by channel, by the same
  /// samples' estimate of white (D65) and multiplied by white's exact XYZ (a self-normalised
  /// estimator: exact for spectra proportional to D65, i.e. grey surfaces under white light, so
  /// the wavelength sampling's colour noise cancels there; consistent, bias O(1/(4 spp)));
  /// unbiased = the plain average of the samples' XYZ
  enum class SpectralFilm { ratio, unbiased };
  SpectralFilm spectral_film = SpectralFilm::ratio;
};

/// [caustics]: light through dielectrics onto diffuse surfaces, by photon tracing from the lights
/// (render/photon/caustic_map.h; rules for the automatic values in docs/render.md).
struct CausticSettings {
  /// false: dielectrics cast full shadows, as a Whitted tracer (the POV-Ray comparison scenes)
  bool enabled = true;
  /// photons aimed at the dielectrics, all lights together; empty = automatic
  std::optional<long long> photons;
  /// radius of the density estimate [scene units]; empty = automatic
  std::optional<double> radius;
};

class LatLongMap;

/// [environment]: what rays that leave the scene see (render/light/environment.h).
/// [[environment.panels]]: a rectangle of uniform radiance in the sky (a soft box, a window).
struct PanelDescription {
  /// unit vector towards the panel's centre
  Vec3d direction{0.0, 1.0, 0.0};
  /// full angular width and height [degrees] seen from the scene, (0, 170); the width runs
  /// horizontally (perpendicular to the sky's up and the direction)
  double width_deg = 20.0, height_deg = 20.0;
  /// radiance = color * intensity (linear RGB)
  RgbD color{1.0, 1.0, 1.0};
  double intensity = 1.0;
  /// width of the soft border [degrees], [0, 30]
  double edge_deg = 1.0;
};

struct EnvironmentDescription {
  enum class Kind { constant, sky, latlong };
  /// constant: [image] background everywhere
  Kind kind = Kind::constant;
  RgbD zenith{0.15, 0.3, 0.65}, horizon{0.8, 0.85, 0.9}, ground{0.25, 0.22, 0.2};
  /// unit vector to the zenith
  Vec3d up{0.0, 1.0, 0.0};
  /// gradient exponent, (0, 10]
  double exponent = 0.5;
  /// scales zenith, horizon and ground (sky) or the image (latlong), >= 0
  double intensity = 1.0;
  /// latlong: the Radiance .hdr file as written (relative to base_dir), and the image once read
  /// (the parser reads it; build_scene reads `file` when it is null)
  std::string file;
  std::shared_ptr<const LatLongMap> map;
  /// latlong: turn of the image about +y [degrees], right-handed, [-360, 360]
  double rotation_deg = 0.0;
  /// sky: panels over the gradient
  std::vector<PanelDescription> panels;
  /// whether the environment lights matte and phong surfaces (render/light/environment_lighting.h)
  bool light_surfaces = false;
  /// shadow rays per shading point and camera sample where an opaque object may hide the sky,
  /// 1..1024 (8x in partly hidden places, at most 64)
  int occlusion_samples = 16;
  /// aerial perspective distance [scene units], 0 (none) or (0, 1e9]
  double haze_distance = 0.0;
};

struct CameraDescription {
  Vec3d position{0.0, 0.0, 5.0};
  Vec3d look_at{0.0, 0.0, 0.0};
  /// unit vector
  Vec3d up{0.0, 1.0, 0.0};
  /// full vertical field of view [degrees], in (0, 180)
  double vertical_fov_deg = 40.0;
  /// medium the camera sits in; empty: the outermost medium of the scene (see build_scene)
  std::string medium;
};

struct AmbientDescription {
  RgbD color{1.0, 1.0, 1.0};
  double intensity = 0.0;
};

struct LightDescription {
  enum class Kind { point, sphere };
  enum class Falloff { none, inverse_square };
  /// point: the light; sphere: its centre
  Vec3d position{0.0, 10.0, 0.0};
  RgbD color{1.0, 1.0, 1.0};
  double intensity = 1.0;
  /// "none" as in POV-Ray; inverse_square divides by the squared distance [scene units^2]
  /// (sphere lights: see render/light/sphere_light.h)
  Falloff falloff = Falloff::none;
  Kind kind = Kind::point;
  /// sphere: radius [scene units], > 0; its radiance is colour * intensity / (pi radius^2), so it
  /// lights like a point light of the same intensity at its centre (render/light/sphere_light.h)
  double radius = 0.0;
  /// sphere: shadow rays per shading point and camera sample (stratified, low-discrepancy)
  int samples = 4;
};

struct MediumDescription {
  std::string name;
  /// constant index of refraction, used when `spec` is empty (media built in code)
  double ior = 1.0;
  /// a full [media.NAME] description (preset, Sellmeier, ..., absorption): see
  /// render/media/medium.h; build_scene() resolves and validates it
  std::optional<media::MediumSpec> spec;
};

struct TextureDescription {
  enum class Kind { solid, checker, noise };
  Kind kind = Kind::solid;
  /// noise (render/material/noise.h): the pattern ("perlin", "worley", "wood", "slate"), colour 0
  /// at value 0 and colour 1 at value 1 (checker_colors), feature size (checker_size; wood: the
  /// plank width) and origin (checker_offset), octaves, and the bump height [m] of value 1
  std::string noise_pattern = "perlin";
  int noise_octaves = 5;
  double bump_m = 0.0;
  RgbD color{0.8, 0.8, 0.8};
  std::array<RgbD, 2> checker_colors{RgbD{0.9, 0.9, 0.9}, RgbD{0.1, 0.1, 0.1}};
  /// checker cell size [scene units]
  double checker_size = 1.0;
  Vec3d checker_offset{0.0, 0.0, 0.0};
};

struct MaterialDescription {
  enum class Kind { matte, metal, phong, emissive };
  std::string name;
  Kind kind = Kind::matte;
  TextureDescription texture;
  double ka = 1.0, kd = 1.0, ks = 0.0, shininess = 32.0;
  double reflectance = 0.0, transmittance = 0.0, ior = 1.0;
  RgbD emission{1.0, 1.0, 1.0};
  double emission_intensity = 1.0;
  /// metal, phong: perceptual roughness in [0, 1] of the mirror term (GGX alpha = roughness^2,
  /// render/material/microfacet.h); 0 = a perfect mirror
  double roughness = 0.0;
};

struct ObjectDescription {
  enum class Shape { mesh, sphere, box, plane };
  Shape shape = Shape::sphere;
  /// where the object came from, for error messages ("objects[2]" or a caller's label)
  std::string label;
  // sphere
  Vec3d center{0.0, 0.0, 0.0};
  double radius = 1.0;
  // box
  Vec3d box_min{-1.0, -1.0, -1.0}, box_max{1.0, 1.0, 1.0};
  // plane
  Vec3d point{0.0, 0.0, 0.0};
  Vec3d normal{0.0, 1.0, 0.0};
  // mesh: either a file (OBJ, absolute or relative to SceneDescription::base_dir) or a mesh in
  // memory; rotate (about x, then y, then z, right-handed, degrees), scale, then translate is
  // applied to it.
  std::filesystem::path mesh_file;
  std::shared_ptr<const TriangleMesh> mesh;
  Vec3d rotate_deg{0.0, 0.0, 0.0};
  double scale = 1.0;
  Vec3d translate{0.0, 0.0, 0.0};
  /// replace the mesh's normals by area-weighted smooth normals
  bool smooth_normals = false;
  /// opaque object: the material's name. Dielectric interface: material empty, inside and
  /// outside name the media (the surface must be closed and outward oriented).
  std::string material;
  std::string inside, outside;
  /// dielectric interface: perceptual roughness in [0, 1] (GGX alpha = roughness^2,
  /// render/material/microfacet.h); 0 = optically smooth, the exact Whitted split
  double roughness = 0.0;

  bool is_dielectric() const { return material.empty(); }
};

struct SceneDescription {
  ImageSettings image;
  CausticSettings caustics;
  EnvironmentDescription environment;
  CameraDescription camera;
  AmbientDescription ambient;
  std::vector<LightDescription> lights;
  /// "vacuum" (n = 1) is always defined and need not be listed
  std::vector<MediumDescription> media;
  std::vector<MaterialDescription> materials;
  std::vector<ObjectDescription> objects;
  /// folder relative mesh files are resolved against (the scene file's folder)
  std::filesystem::path base_dir;
  /// the scene file, for error messages ("" when built in code)
  std::string source_name;

  /// Convenience for code-built scenes: adds a closed dielectric mesh between two media.
  ObjectDescription& add_dielectric_mesh(std::shared_ptr<const TriangleMesh> mesh,
                                         std::string inside, std::string outside,
                                         std::string label = "") {
    ObjectDescription o;
    o.shape = ObjectDescription::Shape::mesh;
    o.mesh = std::move(mesh);
    o.inside = std::move(inside);
    o.outside = std::move(outside);
    o.label = label.empty() ? "objects[" + std::to_string(objects.size()) + "]" : std::move(label);
    objects.push_back(std::move(o));
    return objects.back();
  }
};

}  // namespace thaw::render
