// Built-in media; see medium_library.h.
#include "render/media/medium_library.h"

#include "embedded/media_library_toml.h"
#include "src/common/toml_table.h"

namespace thaw::render::media {

const std::vector<MediumSpec>& medium_presets() {
  static const std::vector<MediumSpec> presets = [] {
    const std::string source = "data/optics/media.toml (built in)";
    const TomlTable root = TomlTable::parse_string(std::string(media_library_toml), source);
    std::vector<MediumSpec> out;
    for (const std::string& name : root.keys())
      out.push_back(parse_medium_spec(root.table(name), name, /*library_entry=*/true));
    root.check_no_unknown_keys();
    return out;
  }();
  return presets;
}

const MediumSpec* find_medium_preset(const std::string& name) {
  for (const MediumSpec& p : medium_presets())
    if (p.name == name) return &p;
  return nullptr;
}

std::string medium_preset_names() {
  std::string s;
  for (const MediumSpec& p : medium_presets()) s += (s.empty() ? "" : ", ") + p.name;
  return s;
}

}  // namespace thaw::render::media
