#pragma once
// The [environment] section's keys, one row each (base/key_table.h): the key, its kind, the
// GUI's label and unit, the documented default and meaning, the EnvironmentDescription field it
// sets and the rule that checks it (render/scene/scene_rules.h); a kind's own keys (the sky's
// colours, the map's file) apply to it alone. The scene parser and docs/render.md
// (tests/render/scene/test_section_keys.cpp holds the page to the table) read it; the sky's
// [[environment.panels]] and the map's loading are the parser's. Knows nothing of TOML or Qt.
#include <span>

#include "base/key_table.h"
#include "render/scene/scene_description.h"

namespace thaw::render {

using EnvironmentKey = KeyRow<EnvironmentDescription>;

/// Every [environment] key, in the order the parser reads them (kind first: the others depend
/// on it).
std::span<const EnvironmentKey> environment_keys();

}  // namespace thaw::render
