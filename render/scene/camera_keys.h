#pragma once
// The [camera] section's keys, one row each (base/key_table.h): the key, its kind, the GUI's
// label and unit, the documented default and meaning, and the CameraDescription field it sets.
// The scene parser, the GUI's camera form and docs/render.md
// (tests/render/scene/test_section_keys.cpp holds the page to the table) read it; the rules
// between the keys (a view direction, an up not along it) are camera_problem's
// (render/scene/scene_rules.h). A new [camera] key is one row here plus its use. Knows nothing
// of TOML or Qt.
#include <span>
#include <string_view>

#include "base/key_table.h"
#include "render/scene/scene_description.h"

namespace thaw::render {

using CameraKey = KeyRow<CameraDescription>;

/// Every [camera] key, in the order the parser reads them.
std::span<const CameraKey> camera_keys();

}  // namespace thaw::render
