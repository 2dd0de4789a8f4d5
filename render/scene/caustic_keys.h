#pragma once
// The [caustics] section's keys, one row each (base/key_table.h): the key, its kind, the GUI's
// label, the documented default and meaning, the CausticSettings field it sets and the rule that
// checks it (render/scene/scene_rules.h). The scene parser, find_scene_problem, the GUI's Render
// tab and docs/render.md (tests/render/scene/test_section_keys.cpp holds the page to the table)
// read it: a new [caustics] key is one row here plus its use. Knows nothing of TOML or Qt.
#include <span>

#include "base/key_table.h"
#include "render/scene/scene_description.h"

namespace thaw::render {

using CausticKey = KeyRow<CausticSettings>;

/// Every [caustics] key, in the order the parser reads and the rules check them.
std::span<const CausticKey> caustic_keys();

}  // namespace thaw::render
