#include "render/scene/image_keys.h"

#include <array>

#include "render/film/filter.h"
#include "render/scene/scene_rules.h"

namespace thaw::render {
namespace {

using S = ImageSettings;
using IntegerKey = thaw::IntegerKey<S>;
using NumberKey = thaw::NumberKey<S>;
using FlagKey = thaw::FlagKey<S>;
using ColourKey = thaw::ColourKey<S>;
using ChoiceKey = thaw::ChoiceKey<S>;
using AutoFlagKey = thaw::AutoFlagKey<S>;

constexpr std::array<std::string_view, 3> kFilterNames{"box", "gaussian", "mitchell"};
constexpr std::array<std::string_view, 3> kDispersionNames{"adaptive", "split", "hero"};
constexpr std::array<std::string_view, 2> kPatternNames{"shared", "per_pixel"};
constexpr std::array<std::string_view, 2> kFilmNames{"ratio", "unbiased"};
constexpr std::array<std::string_view, 2> kToneNames{"clip", "agx"};

double filter_radius_of_filter(const S& s) {
  return default_filter_radius(s.filter);
}

const ImageKey kImageKeys[] = {
    {"width", "Width", "px", "640", "pixels, 1..16384; width x height at most 2^26",
     IntegerKey{&S::width, image_side_problem}},
    {"height", "Height", "px", "480", "pixels, 1..16384; width x height at most 2^26",
     IntegerKey{&S::height, image_side_problem}},
    {"samples_per_pixel", "Samples per pixel", "", "1",
     "camera samples per pixel, the cap of adaptive sampling, 1..65536; 1 = one ray through the "
     "pixel centre (as POV-Ray), whatever the filter",
     IntegerKey{&S::samples_per_pixel, samples_per_pixel_problem}},
    {"adaptive", "Adaptive sampling", "", "true",
     "adaptive anti-aliasing (see \"Anti-aliasing\" below): `min_samples` everywhere, doubled "
     "while the pixel's standard error exceeds `adaptive_threshold`, up to `samples_per_pixel`; "
     "false = every pixel takes `samples_per_pixel`",
     FlagKey{&S::adaptive}},
    {"min_samples", "Minimum samples", "", "2",
     "the first batch of an adaptive pixel (pairs of samples), 2..65536; in spectral renders also "
     "the number of wavelength strata every pixel averages (one per pair)",
     IntegerKey{&S::min_samples, min_samples_problem}},
    {"adaptive_threshold", "Adaptive threshold", "", "0.01",
     "standard error of a pixel's mean at which it stops, in display units (exposed, clamped, "
     "sRGB-encoded: 1/255 is one 8-bit step), 1e-4..1",
     NumberKey{&S::adaptive_threshold, adaptive_threshold_problem}},
    {"filter", "Filter", "", "\"gaussian\"",
     "reconstruction filter: \"box\", \"gaussian\" (exp(-x^2/2s^2) - exp(-r^2/2s^2), s = r/3) or "
     "\"mitchell\" (Mitchell-Netravali, B = C = 1/3); separable, importance-sampled",
     ChoiceKey{kFilterNames, [](const S& s) { return std::string_view(filter_name(s.filter)); },
               [](S& s, std::string_view name) {
                 const auto kind = filter_kind_from_name(name);
                 if (kind) s.filter = *kind;
                 return kind.has_value();
               }}},
    {"filter_radius", "Filter radius", "px", "box 0.5, gaussian 1.5, mitchell 2",
     "the filter's half-width [pixels], 0.5..4",
     NumberKey{&S::filter_radius, filter_radius_problem, filter_radius_of_filter}},
    {"texture_filter", "Texture filtering", "", "true",
     "with `samples_per_pixel` > 1, checker textures are averaged over each camera sample's ray "
     "cone (see \"Anti-aliasing\"): no moire at the horizon, in reflections or through the ice; "
     "at 1 sample per pixel textures are point-sampled (POV-Ray)",
     FlagKey{&S::texture_filter}},
    {"max_depth", "Ray depth", "", "10",
     "levels of the ray tree, the camera ray being level 1 (POV-Ray `max_trace_level`), 1..256; "
     "a branch cut at this level returns black (section \"Ray depth\" below)",
     IntegerKey{&S::max_depth, max_depth_problem}},
    {"background", "Background", "", "[0, 0, 0]", "radiance of every ray that leaves the scene",
     ColourKey{&S::background}},
    {"min_weight", "Minimum weight", "", "1/255",
     "branches whose weight (product of Fresnel/mirror factors) falls below this are not traced "
     "(POV-Ray `adc_bailout`)",
     NumberKey{&S::min_weight, min_weight_problem}},
    {"exposure", "Exposure", "stops", "0", "PNG scale `2^exposure` [stops], -64..64",
     NumberKey{&S::exposure, exposure_problem}},
    {"tone", "Tone", "", "\"agx\"",
     "view transform of PNG outputs (render/film/view_transform.h): \"agx\" (a filmic roll-off "
     "after Sobotka's AgX: highlights are not clipped, bright colours desaturate towards white) or "
     "\"clip\" (exposed and clamped to [0, 1], as POV-Ray; the comparison scenes set it); PFM and "
     "EXR stay linear",
     ChoiceKey{
         kToneNames, [](const S& s) { return kToneNames[static_cast<std::size_t>(s.view)]; },
         [](S& s, std::string_view name) { return set_enum_by_name(s.view, kToneNames, name); }}},
    {"spectral", "Spectral", "", "\"auto\"",
     "spectral transport (docs/dispersion.md): \"auto\" = on iff a medium is dispersive or "
     "absorbs; false = RGB (n_d, absorption per channel: docs/dispersion.md \"Absorption in RGB "
     "mode\")",
     AutoFlagKey{[](const S& s) -> std::optional<bool> {
                   if (s.spectral == S::Spectral::automatic) return std::nullopt;
                   return s.spectral == S::Spectral::on;
                 },
                 [](S& s, std::optional<bool> v) {
                   s.spectral =
                       !v ? S::Spectral::automatic : (*v ? S::Spectral::on : S::Spectral::off);
                 }}},
    {"dispersion", "Dispersion", "", "\"adaptive\"",
     "at a dispersive refraction: \"adaptive\", \"split\" or \"hero\" (docs/dispersion.md)",
     ChoiceKey{kDispersionNames,
               [](const S& s) { return kDispersionNames[static_cast<std::size_t>(s.dispersion)]; },
               [](S& s, std::string_view name) {
                 const auto d = dispersion_from_name(name);
                 if (d) s.dispersion = *d;
                 return d.has_value();
               }}},
    {"dispersion_wavelengths", "Dispersion wavelengths", "", "10",
     "adaptive: wavelengths probed for fringes; split: wavelengths traced per sample (rounded up "
     "to a multiple of 4), 4..1024",
     IntegerKey{&S::dispersion_wavelengths, dispersion_wavelengths_problem}},
    {"dispersion_resolution_nm", "Dispersion resolution", "nm", "4.0",
     "adaptive: width to which a fringe's colour jump is located [nm], 0.05..100",
     NumberKey{&S::dispersion_resolution_nm, dispersion_resolution_problem}},
    {"wavelength_pattern", "Wavelength pattern", "", "\"shared\"",
     "\"shared\" (every pixel carries the same stratified wavelengths, offset from the seed) or "
     "\"per_pixel\"",
     ChoiceKey{
         kPatternNames,
         [](const S& s) { return kPatternNames[static_cast<std::size_t>(s.wavelength_pattern)]; },
         [](S& s, std::string_view name) {
           const auto p = wavelength_pattern_from_name(name);
           if (p) s.wavelength_pattern = *p;
           return p.has_value();
         }}},
    {"spectral_film", "Spectral film", "", "\"ratio\"",
     "\"ratio\" (each pixel's XYZ normalised by the same samples' estimate of white: no colour "
     "noise on grey surfaces) or \"unbiased\" (the plain average)",
     ChoiceKey{kFilmNames,
               [](const S& s) { return kFilmNames[static_cast<std::size_t>(s.spectral_film)]; },
               [](S& s, std::string_view name) {
                 if (name == "ratio")
                   s.spectral_film = S::SpectralFilm::ratio;
                 else if (name == "unbiased")
                   s.spectral_film = S::SpectralFilm::unbiased;
                 else
                   return false;
                 return true;
               }}},
};

}  // namespace

std::span<const ImageKey> image_keys() {
  return kImageKeys;
}

const ImageKey* find_image_key(std::string_view name) {
  return find_key(image_keys(), name);
}

}  // namespace thaw::render
