#include "render/scene/environment_keys.h"

#include <array>

#include "render/scene/scene_rules.h"

namespace thaw::render {
namespace {

using E = EnvironmentDescription;

constexpr std::array<std::string_view, 3> kKindNames{"constant", "sky", "latlong"};

bool sky(const E& e) {
  return e.kind == E::Kind::sky;
}
bool latlong(const E& e) {
  return e.kind == E::Kind::latlong;
}
bool not_constant(const E& e) {
  return e.kind != E::Kind::constant;
}

const EnvironmentKey kEnvironmentKeys[] = {
    {"kind", "Environment", "", "\"constant\"",
     "what rays leaving the scene see: \"constant\" ([image] `background`), \"sky\" "
     "(render/light/environment.h): a gradient from `horizon` up to `zenith` (L = horizon + "
     "(zenith - horizon) sin(elevation)^`exponent`), `ground` below, joined within 2 degrees of "
     "the horizon, plus optional panels; or \"latlong\": an HDR image (section \"Lat-long "
     "environment maps\"). Seen by camera, reflected and refracted rays; a light of diffuse "
     "surfaces only with `light_surfaces = true`; keys of another kind are errors (unused)",
     ChoiceKey<E>{
         kKindNames, [](const E& e) { return kKindNames[static_cast<std::size_t>(e.kind)]; },
         [](E& e, std::string_view name) { return set_enum_by_name(e.kind, kKindNames, name); },
         "environment"}},
    {"light_surfaces", "Environment lights surfaces", "", "false",
     "any kind: the environment also lights matte and phong surfaces (section \"Environment "
     "lighting\"); off, it is only seen (Whitted)",
     FlagKey<E>{&E::light_surfaces}},
    {"occlusion_samples", "Environment shadow samples", "", "16",
     "with `light_surfaces`: shadow rays per shading point and camera sample where an opaque "
     "object may hide part of the sky (8x where they disagree, at most 64), 1..1024",
     IntegerKey<E>{&E::occlusion_samples, environment_samples_problem}},
    {"haze_distance", "Haze distance", "", "0",
     "any kind: aerial perspective distance [scene units], 0 (none) .. 1e9: a surface at "
     "distance t seen through the camera's medium fades to the sky at the horizon by exp(-t / "
     "haze_distance) (section \"Environment lighting\")",
     NumberKey<E>{&E::haze_distance, environment_haze_problem}},
    {"zenith",
     "Zenith",
     "",
     "[0.15, 0.3, 0.65]",
     "sky: linear RGB, non-negative",
     ColourKey<E>{&E::zenith},
     {},
     sky},
    {"horizon",
     "Horizon",
     "",
     "[0.8, 0.85, 0.9]",
     "sky: linear RGB, non-negative",
     ColourKey<E>{&E::horizon},
     {},
     sky},
    {"ground",
     "Ground",
     "",
     "[0.25, 0.22, 0.2]",
     "sky: linear RGB, non-negative",
     ColourKey<E>{&E::ground},
     {},
     sky},
    {"up",
     "Zenith direction",
     "",
     "[0, 1, 0]",
     "sky: unit zenith direction",
     VectorKey<E>{&E::up, true, false},
     {},
     sky},
    {"exponent",
     "Gradient exponent",
     "",
     "0.5",
     "sky: gradient exponent in (0, 10]",
     NumberKey<E>{&E::exponent, environment_exponent_problem},
     {},
     sky},
    {"file",
     "Map file",
     "",
     "required (latlong)",
     "latlong: Radiance `.hdr` (RGBE, flat or run-length encoded) or OpenEXR `.exr` (R, G, B "
     "channels, half or float; by the extension, any case), relative to the scene file; twice as "
     "wide as high, 2 x 1 to 16384 x 8192 texels",
     TextKey<E>{&E::file, true},
     {},
     latlong},
    {"rotation_deg",
     "Map rotation",
     "deg",
     "0",
     "latlong: turn about +y [degrees], right-handed, -360..360 (+90 brings the image's centre "
     "from -z to -x)",
     NumberKey<E>{&E::rotation_deg, environment_rotation_problem},
     {},
     latlong},
    {"intensity",
     "Environment intensity",
     "",
     "1",
     "sky and latlong: scale of the colours or of the image, 0..1e6",
     NumberKey<E>{&E::intensity, environment_intensity_problem},
     {},
     not_constant},
};

}  // namespace

std::span<const EnvironmentKey> environment_keys() {
  return kEnvironmentKeys;
}

}  // namespace thaw::render
