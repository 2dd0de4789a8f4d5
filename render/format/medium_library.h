#pragma once
// The built-in library of optical media (vacuum, air, water at 0 and 20 C, ice Ih, N-BK7,
// N-SF10, fused silica, diamond) with their sources: data/optics/media.toml, embedded in the
// binary at build time so the file that documents the data is the data.
#include <string>
#include <vector>

#include "render/media/medium.h"

namespace thaw::render::media {

/// All presets, sorted by name (parsed once, on first use; thread-safe).
const std::vector<MediumSpec>& medium_presets();
/// The preset called `name`, or nullptr.
const MediumSpec* find_medium_preset(const std::string& name);
/// "vacuum, air, water-20c, ..." for error messages.
std::string medium_preset_names();
/// `spec` with its preset (if any) replaced by the preset's index, absorption (unless `spec`
/// gives its own) and source; an unknown preset is a thaw::UserError listing the known ones.
MediumSpec resolve_preset(MediumSpec spec);

}  // namespace thaw::render::media
