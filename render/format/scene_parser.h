#pragma once
// Reads a thaw scene file (TOML; keys documented in docs/render.md) into a SceneDescription.
// Every key is checked: unknown keys, wrong types, out-of-range values (the rules of
// render/scene/scene_rules.h) and unknown medium or material names are thaw::UserError naming the
// file, line and key. Meshes are not loaded here
// (build_scene does that), so parsing is cheap and testable from strings.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "base/format/toml_table.h"
#include "render/scene/scene_description.h"
#include "render/scene/scene_rules.h"

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

}  // namespace thaw::render
