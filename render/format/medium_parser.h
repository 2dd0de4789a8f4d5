#pragma once
// [media.NAME] TOML tables -> MediumSpec (render's file-format layer; the keys are listed in
// render/media/medium.h). Knows nothing of the library or of building a Medium.
#include <string>

#include "render/media/medium.h"

namespace thaw {
class TomlTable;
}

namespace thaw::render::media {

/// Reads a [media.NAME] table. Malformed values, several index sources or none throw
/// thaw::UserError naming the key. Keys are marked as read, so the caller's
/// check_no_unknown_keys() reports typos. `library_entry` also accepts description, source and
/// absorption_source and rejects preset.
MediumSpec parse_medium_spec(const TomlTable& table, const std::string& name,
                             bool library_entry = false);

}  // namespace thaw::render::media
