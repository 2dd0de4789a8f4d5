#pragma once
// The [image] section's keys, one row each (pbrt-v4's ParameterDictionary, Mitsuba 3's
// props.get beside the plugin's documentation): the key, its kind, the GUI's label and unit, the
// documented default and meaning, the ImageSettings field it sets and the rule that checks it
// (render/scene/scene_rules.h). The scene parser, find_scene_problem, the GUI's Render tab and
// docs/render.md (tests/render/scene/test_image_keys.cpp holds the page to the table) all read
// it: a new [image] key is one row here plus its use. Knows nothing of TOML, flags or Qt.
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "render/scene/scene_description.h"

namespace thaw::render {

/// An integer field and its rule.
struct IntegerKey {
  int ImageSettings::*field;
  std::optional<std::string> (*rule)(long long);
};
/// A real field and its rule; `absent` (when set) gives the value of a key the file leaves out
/// from the settings read so far (filter_radius follows the filter).
struct NumberKey {
  double ImageSettings::*field;
  std::optional<std::string> (*rule)(double);
  double (*absent)(const ImageSettings&) = nullptr;
};
struct FlagKey {
  bool ImageSettings::*field;
};
/// Linear RGB, non-negative.
struct ColourKey {
  RgbD ImageSettings::*field;
};
/// One of a list of names ("gaussian"); `set` returns false for a name not in the list.
struct ChoiceKey {
  std::span<const std::string_view> names;
  std::string_view (*get)(const ImageSettings&);
  bool (*set)(ImageSettings&, std::string_view name);
};
/// true, false or "auto" (spectral).
struct AutoFlagKey {
  std::optional<bool> (*get)(const ImageSettings&);
  void (*set)(ImageSettings&, std::optional<bool> value);
};

struct ImageKey {
  std::string_view name;          ///< the key in [image]
  std::string_view label;         ///< the GUI's label
  std::string_view unit;          ///< unit of the value ("px", "stops"), "" for none
  std::string_view default_text;  ///< the default as docs/render.md writes it
  std::string_view doc;           ///< its meaning and accepted range, as docs/render.md writes it
  std::variant<IntegerKey, NumberKey, FlagKey, ColourKey, ChoiceKey, AutoFlagKey> value;
};

/// Every [image] key, in the order the parser reads them (filter before filter_radius).
std::span<const ImageKey> image_keys();
/// The row of `name`, or nullptr.
const ImageKey* find_image_key(std::string_view name);
/// The row's rule applied to its value in `image` (integer and real keys; the other kinds can
/// only hold accepted values), or nullopt.
std::optional<std::string> image_key_problem(const ImageKey& key, const ImageSettings& image);

}  // namespace thaw::render
