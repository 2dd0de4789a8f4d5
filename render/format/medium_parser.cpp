// Reading [media.NAME] tables; see medium_parser.h.
#include "render/format/medium_parser.h"

#include <vector>

#include "base/error.h"
#include "base/format/toml_table.h"
#include "render/media/scattering.h"

namespace thaw::render::media {
namespace {

/// absorption_per_m: a number or a { wavelength_nm, per_m } table.
Absorption parse_absorption(const TomlTable& t) {
  if (!t.is<TomlTable>("absorption_per_m"))
    return Absorption::constant(t.get_double("absorption_per_m"));
  const TomlTable table = t.table("absorption_per_m");
  return Absorption::table(table.get_doubles("wavelength_nm"), table.get_doubles("per_m"));
}

/// scattering_per_m and asymmetry, or bubbles = { air_fraction, radius_m } (cloudy ice,
/// render/media/scattering.h): each bad value is the file's error at its key.
void parse_scattering(const TomlTable& t, MediumSpec& spec) {
  if (t.has("bubbles") && t.has("scattering_per_m"))
    t.fail("bubbles", "give either bubbles or scattering_per_m, not both");
  if (t.has("scattering_per_m")) {
    const double s = t.get_double("scattering_per_m");
    if (auto p = scattering_problem(s)) t.fail("scattering_per_m", *p);
    spec.scattering_per_m = s;
  }
  if (t.has("bubbles")) {
    const TomlTable b = t.table("bubbles");
    const double f = b.get_double("air_fraction"), r = b.get_double("radius_m");
    if (auto p = air_fraction_problem(f)) b.fail("air_fraction", *p);
    if (auto p = bubble_radius_problem(r)) b.fail("radius_m", *p);
    spec.scattering_per_m = bubble_scattering_per_m(f, r);
    spec.asymmetry = kBubbleAsymmetry;
  }
  if (t.has("asymmetry")) {
    const double g = t.get_double("asymmetry");
    if (auto p = asymmetry_problem(g)) t.fail("asymmetry", *p);
    spec.asymmetry = g;
  }
}

}  // namespace

MediumSpec parse_medium_spec(const TomlTable& t, const std::string& name, bool library_entry) {
  MediumSpec spec;
  spec.name = name;
  spec.file = t.source_name();
  spec.key = t.path();

  const std::vector<std::string> sources = {"preset", "ior",   "sellmeier",
                                            "cauchy", "table", "iapws97"};
  std::vector<std::string> given;
  for (const auto& k : sources)
    if (t.has(k)) given.push_back(k);
  if (given.size() > 1)
    t.fail(given[1],
           "give exactly one of preset, ior, sellmeier, cauchy, table, iapws97 (also found '" +
               given[0] + "')");
  if (given.empty())
    t.fail("", "medium '" + name +
                   "' needs an index of refraction: preset = \"...\" (see `thaw materials`), ior, "
                   "sellmeier, cauchy, table or iapws97");

  const std::string& which = given[0];
  if (which == "preset") {
    if (library_entry) t.fail("preset", "a library entry cannot refer to another preset");
    spec.preset = t.get_string("preset");
  } else if (which == "ior") {
    spec.ior = IorModel::constant(t.get_double("ior"));
  } else if (which == "sellmeier") {
    const TomlTable s = t.table("sellmeier");
    const std::string form = s.get_string("form", "n^2-1");
    if (form != "n^2-1" && form != "n-1")
      s.fail("form",
             "must be \"n^2-1\" (glasses, liquids) or \"n-1\" (gases), got \"" + form + "\"");
    auto b = s.get_doubles("B");
    auto c = s.get_doubles("C");
    spec.ior = form == "n-1" ? IorModel::sellmeier_gas(std::move(b), std::move(c))
                             : IorModel::sellmeier(std::move(b), std::move(c));
  } else if (which == "cauchy") {
    const TomlTable c = t.table("cauchy");
    spec.ior = IorModel::cauchy(c.get_double("A"), c.get_double("B", 0.0), c.get_double("C", 0.0));
  } else if (which == "table") {
    const TomlTable c = t.table("table");
    spec.ior = IorModel::table(c.get_doubles("wavelength_nm"), c.get_doubles("n"));
  } else {
    const TomlTable c = t.table("iapws97");
    spec.ior = IorModel::iapws97(c.get_double("temperature_c"), c.get_double("density_kg_m3"));
  }

  if (t.has("absorption_per_m")) spec.absorption = parse_absorption(t);
  if (t.has("absorption_scale")) spec.absorption_scale = t.get_double("absorption_scale");
  parse_scattering(t, spec);
  if (library_entry) {
    spec.description = t.get_string("description", "");
    spec.source = t.get_string("source");
    spec.absorption_source = t.get_string("absorption_source", "");
  }
  return spec;
}

}  // namespace thaw::render::media
