// `thaw materials [NAME] [--wavelength-nm L]`: lists the built-in optical media
// (data/optics/media.toml) or prints one medium's index and absorption. Parsing and help only;
// the data and models live in render/media.
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "base/error.h"
#include "render/format/medium_library.h"
#include "render/media/medium.h"
#include "src/cli/commands.h"

namespace thaw::cli {
namespace {

struct MaterialsArgs {
  std::string name;
  std::optional<double> wavelength_nm;
};

void list_library() {
  std::printf("%-13s %-16s %9s %7s  %s\n", "name", "model", "n_d", "V_d", "source");
  for (const render::media::MediumSpec& p : render::media::medium_presets()) {
    const auto& ior = *p.ior;
    const double v = ior.abbe_number();
    char abbe[32] = "-";
    if (std::isfinite(v)) std::snprintf(abbe, sizeof abbe, "%.1f", v);
    std::printf("%-13s %-16s %9.6f %7s  %s\n", p.name.c_str(), ior.kind_name().c_str(),
                ior.n_at(render::media::kFraunhoferD_nm), abbe, p.source.c_str());
  }
  std::printf(
      "n_d at 587.56 nm (relative to vacuum unless the source says air); V_d = (n_d - 1) / (n_F - "
      "n_C).\n"
      "Use one in a scene with [media.NAME] preset = \"...\"; see docs/dispersion.md.\n");
}

void show_medium(const MaterialsArgs& a) {
  const render::media::MediumSpec* p = render::media::find_medium_preset(a.name);
  if (!p)
    throw UserError(
        "", "materials",
        "unknown medium \"" + a.name + "\"; known: " + render::media::medium_preset_names());
  const render::media::Medium m = render::media::build_medium(*p);
  if (a.wavelength_nm) {
    const double l = *a.wavelength_nm;
    if (!(l >= render::kLambdaMinNm && l <= render::kLambdaMaxNm))
      throw UserError(
          "", "--wavelength-nm",
          "must be within the rendered range 380-780 nm (got " + CLI::detail::to_string(l) + ")");
    std::printf("%s at %.2f nm: n = %.6f, absorption = %.6g /m\n", m.name().c_str(), l, m.n_at(l),
                m.absorption_per_m_at(l));
    return;
  }
  std::printf("%s: %s\n  index: %s, %s\n", p->name.c_str(), p->description.c_str(),
              m.ior_model().kind_name().c_str(), p->source.c_str());
  if (!p->absorption_source.empty())
    std::printf("  absorption: %s\n", p->absorption_source.c_str());
  std::printf("  %9s %10s %14s\n", "lambda_nm", "n", "absorption_/m");
  for (double l : {400.0, render::media::kFraunhoferF_nm, 500.0, render::media::kFraunhoferD_nm,
                   600.0, render::media::kFraunhoferC_nm, 700.0, 780.0})
    std::printf("  %9.2f %10.6f %14.6g\n", l, m.n_at(l), m.absorption_per_m_at(l));
}

}  // namespace

void register_materials(CLI::App& app) {
  auto args = std::make_shared<MaterialsArgs>();
  CLI::App* cmd = app.add_subcommand(
      "materials",
      "List the built-in optical media (index of refraction models and absorption, "
      "with sources), or print one medium's n and absorption coefficient.");
  cmd->add_option("name", args->name, "medium to show (e.g. water-0c); omit to list all");
  cmd->add_option(
      "--wavelength-nm", args->wavelength_nm,
      "print n and the absorption coefficient [1/m] at this vacuum wavelength [nm], 380-780");
  cmd->callback([args] {
    if (args->name.empty()) {
      if (args->wavelength_nm) throw UserError("", "--wavelength-nm", "needs a medium NAME");
      list_library();
    } else {
      show_medium(*args);
    }
  });
}

}  // namespace thaw::cli
