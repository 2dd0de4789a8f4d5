#pragma once
// Scenes shared by the photon tests: built from TOML text like a user's file.
#include <string>

#include "render/format/scene_parser.h"
#include "render/scene/scene.h"

namespace thaw::render::photon::test {

inline Scene scene_from(const std::string& toml) {
  return build_scene(parse_scene_string(toml, "test.toml", ""));
}

inline const std::string kCamera = R"(
[camera]
position = [0.0, 3.0, 8.0]
look_at = [0.0, 0.0, 0.0]
vertical_fov_deg = 40.0
)";

/// A ball of radius 1 of medium `glass` (its keys: "ior = 1.31", "preset = \"n-bk7\"") at the
/// origin in vacuum over a matte plane at
/// y = `floor_y`, a point light at `light` ("[x, y, z]") with inverse-square falloff; `extra`
/// is appended (image keys go through `image`).
inline Scene ball_over_floor(const std::string& glass, double floor_y, const std::string& light,
                             const std::string& image = "", const std::string& caustics = "",
                             const std::string& extra = "") {
  return scene_from("[image]\n" + image + "\n[caustics]\n" + caustics + R"(
[[lights]]
position = )" + light +
                    R"(
falloff = "inverse_square"
intensity = 100.0
[media.glass]
)" + glass + R"(
[materials.white]
kind = "matte"
color = [1.0, 1.0, 1.0]
[[objects]]
shape = "sphere"
center = [0.0, 0.0, 0.0]
radius = 1.0
inside = "glass"
outside = "vacuum"
[[objects]]
shape = "plane"
point = [0.0, )" + std::to_string(floor_y) +
                    R"(, 0.0]
normal = [0.0, 1.0, 0.0]
material = "white"
)" + extra + kCamera);
}

}  // namespace thaw::render::photon::test
