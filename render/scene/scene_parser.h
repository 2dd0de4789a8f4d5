#pragma once
// Reads a thaw scene file (TOML; keys documented in docs/render.md) into a SceneDescription.
// Every key is checked: unknown keys, wrong types, out-of-range values and unknown medium or
// material names are thaw::UserError naming the file, line and key. Meshes are not loaded here
// (build_scene does that), so parsing is cheap and testable from strings.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "render/scene/scene_description.h"
#include "src/common/toml_table.h"

namespace thaw::render {

/// Parses `path`; relative mesh files are resolved against its folder.
SceneDescription parse_scene_file(const std::filesystem::path& path);

/// Parses scene text; `source_name` names it in errors, `base_dir` resolves mesh files.
SceneDescription parse_scene_string(const std::string& text, const std::string& source_name,
                                    const std::filesystem::path& base_dir = {});

/// Reads the scene keys of `table` (a document's root, or e.g. a scenario's [render] table: keys
/// are then reported as "render.camera.up"). Every key it reads is marked, but unknown keys are
/// not checked here: the owner of the document calls check_no_unknown_keys() once at the end.
/// With camera_optional (thaw run, whose built-in camera frames the shell), a missing [camera]
/// leaves the default CameraDescription instead of being an error.
SceneDescription parse_scene_table(const TomlTable& table, const std::filesystem::path& base_dir,
                                   bool camera_optional = false);

/// Largest accepted image side [pixels] and pixel count.
inline constexpr int kMaxImageSide = 16384;
inline constexpr long long kMaxImagePixels = 1LL << 26;

/// Accepted [image] samples_per_pixel (the cap) and min_samples, [image] adaptive_threshold
/// (display units) and [[lights]] samples of a sphere light.
inline constexpr int kMaxSamplesPerPixel = 65536;
inline constexpr double kMinAdaptiveThreshold = 1e-4, kMaxAdaptiveThreshold = 1.0;
inline constexpr int kMaxLightSamples = 1024;

/// Accepted [image] dispersion_wavelengths and dispersion_resolution_nm [nm].
inline constexpr int kMinDispersionWavelengths = 4, kMaxDispersionWavelengths = 1024;
inline constexpr double kMinDispersionResolutionNm = 0.05, kMaxDispersionResolutionNm = 100.0;

/// [image] dispersion and wavelength_pattern values by name, as in scene files and the flags of
/// `thaw render`; nullopt for an unknown name.
std::optional<ImageSettings::Dispersion> dispersion_from_name(std::string_view name);
std::optional<ImageSettings::WavelengthPattern> wavelength_pattern_from_name(std::string_view name);

}  // namespace thaw::render
