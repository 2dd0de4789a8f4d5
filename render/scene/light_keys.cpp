#include "render/scene/light_keys.h"

#include <array>

#include "render/scene/scene_rules.h"

namespace thaw::render {
namespace {

using L = LightDescription;

constexpr std::array<std::string_view, 2> kKindNames{"point", "sphere"};
constexpr std::array<std::string_view, 2> kFalloffNames{"none", "inverse_square"};

bool sphere(const L& l) {
  return l.kind == L::Kind::sphere;
}

const LightKey kLightKeys[] = {
    {"kind", "Kind", "", "\"point\"",
     "\"point\" or \"sphere\" (an area light: soft shadows; see \"Sphere lights\" below)",
     ChoiceKey<L>{
         kKindNames, [](const L& l) { return kKindNames[static_cast<std::size_t>(l.kind)]; },
         [](L& l, std::string_view name) { return set_enum_by_name(l.kind, kKindNames, name); },
         "light kind"}},
    {"radius",
     "Radius (sphere)",
     "m",
     "required (sphere)",
     "sphere: > 0 [scene units]; the sphere shines with radiance `color * intensity / (pi "
     "radius^2)`",
     NumberKey<L>{&L::radius, light_radius_problem, nullptr, true},
     {},
     sphere},
    {"samples",
     "Shadow samples (sphere)",
     "",
     "4",
     "sphere: shadow rays per shading point and camera sample, 1..1024 (stratified "
     "low-discrepancy); where they disagree (a penumbra) 8x as many, at most 64; twice as many "
     "where all reach the light but something may lie in the way",
     IntegerKey<L>{&L::samples, light_samples_problem},
     {},
     sphere},
    {"position", "Position", "m", "required", "the point, or the sphere's centre",
     VectorKey<L>{&L::position, false, true}},
    {"color", "Colour", "", "[1, 1, 1]", "linear RGB, non-negative", ColourKey<L>{&L::color}},
    {"intensity", "Intensity", "", "1", "intensity I, >= 0",
     NumberKey<L>{&L::intensity, light_intensity_problem}},
    {"falloff", "Falloff", "", "\"none\"",
     "\"none\" (POV-Ray and the reports) or \"inverse_square\"",
     ChoiceKey<L>{kFalloffNames,
                  [](const L& l) { return kFalloffNames[static_cast<std::size_t>(l.falloff)]; },
                  [](L& l, std::string_view name) {
                    return set_enum_by_name(l.falloff, kFalloffNames, name);
                  },
                  "falloff"}},
};

}  // namespace

std::span<const LightKey> light_keys() {
  return kLightKeys;
}

}  // namespace thaw::render
