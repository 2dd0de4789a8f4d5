// Built-in media; see medium_library.h.
#include "render/format/medium_library.h"

#include "base/error.h"
#include "base/format/toml_table.h"
#include "embedded/media_library_toml.h"
#include "render/format/medium_parser.h"

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

MediumSpec resolve_preset(MediumSpec spec) {
  if (spec.preset.empty()) return spec;
  const MediumSpec* preset = find_medium_preset(spec.preset);
  if (!preset)
    throw UserError(spec.file, "key '" + spec.key + ".preset'",
                    "unknown preset \"" + spec.preset + "\" for medium '" + spec.name +
                        "'; known presets: " + medium_preset_names());
  spec.ior = preset->ior;
  if (!spec.absorption) spec.absorption = preset->absorption;
  spec.source = preset->source;
  spec.preset.clear();
  return spec;
}

}  // namespace thaw::render::media
