#pragma once
// The keys of a [[lights]] entry, one row each (base/key_table.h): the key, its kind, the GUI's
// label and unit, the documented default and meaning, the LightDescription field it sets and the
// rule that checks it (render/scene/scene_rules.h); a sphere light's own keys apply to it alone.
// The scene parser, the GUI's light form and docs/render.md
// (tests/render/scene/test_section_keys.cpp holds the page to the table) read it; light_problem
// keeps the rules of a light built in code. Knows nothing of TOML or Qt.
#include <span>

#include "base/key_table.h"
#include "render/scene/scene_description.h"

namespace thaw::render {

using LightKey = KeyRow<LightDescription>;

/// Every [[lights]] key, in the order the parser reads them (kind first: the sphere's keys
/// depend on it).
std::span<const LightKey> light_keys();

}  // namespace thaw::render
