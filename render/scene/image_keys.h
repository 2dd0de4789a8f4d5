#pragma once
// The [image] section's keys, one row each (pbrt-v4's ParameterDictionary, Mitsuba 3's
// props.get beside the plugin's documentation): the key, its kind, the GUI's label and unit, the
// documented default and meaning, the ImageSettings field it sets and the rule that checks it
// (render/scene/scene_rules.h), in base/key_table.h's generic row. The scene parser,
// find_scene_problem, the GUI's Render tab and docs/render.md
// (tests/render/scene/test_image_keys.cpp holds the page to the table) all read it: a new [image]
// key is one row here plus its use. Knows nothing of TOML, flags or Qt.
#include <span>
#include <string_view>

#include "base/key_table.h"
#include "render/scene/scene_description.h"

namespace thaw::render {

/// One [image] key (base/key_table.h).
using ImageKey = KeyRow<ImageSettings>;

/// Every [image] key, in the order the parser reads them (filter before filter_radius).
std::span<const ImageKey> image_keys();
/// The row of `name`, or nullptr.
const ImageKey* find_image_key(std::string_view name);

}  // namespace thaw::render
