// Building media; see medium.h (parsing: medium_parser.h).
#include "render/media/medium.h"

#include <utility>
#include <vector>

#include "base/check.h"
#include "base/error.h"

namespace thaw::render::media {
Medium::Medium(std::string name, IorModel ior, Absorption absorption, std::string source)
    : m_name(std::move(name)),
      m_ior(std::move(ior)),
      m_absorption(std::move(absorption)),
      m_source(std::move(source)) {}

Medium build_medium(const MediumSpec& spec) {
  THAW_CHECK(spec.preset.empty(),
             "medium presets are resolved by the file layer (resolve_preset) before build_medium");
  const std::optional<IorModel>& ior = spec.ior;
  const std::optional<Absorption>& absorption = spec.absorption;
  if (!ior)
    throw UserError(spec.file, "key '" + spec.key + "'",
                    "medium '" + spec.name + "' has no index of refraction");
  ior->validate(spec.file, spec.key);
  Absorption a = absorption.value_or(Absorption()).scaled(spec.absorption_scale.value_or(1.0));
  a.validate(spec.file, spec.key);
  Medium m(spec.name, *ior, std::move(a), spec.source);
  m.set_scattering(spec.scattering_per_m.value_or(0.0), spec.asymmetry.value_or(0.0));
  return m;
}

}  // namespace thaw::render::media
