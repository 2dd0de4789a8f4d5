#include "sim/scenario/scenario_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <vector>

#include "embedded/kDefaultScenarioToml.h"
#include "embedded/kIceWaterMaterialsToml.h"
#include "sim/grid/grid_rules.h"
#include "src/common/error.h"
#include "src/common/toml_table.h"

namespace thaw::sim {

const char* to_string(InnerBoundary kind) {
  return kind == InnerBoundary::symmetry ? "symmetry" : "temperature";
}

const char* to_string(OuterBoundary kind) {
  switch (kind) {
    case OuterBoundary::temperature:
      return "temperature";
    case OuterBoundary::convective:
      return "convective";
    case OuterBoundary::flux:
      return "flux";
    case OuterBoundary::insulated:
      return "insulated";
  }
  return "?";
}

namespace {

/// Shortest text that reads back as the same double ("0.04", not "0.040000000000000001").
std::string num(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

struct Problem {
  std::string key;  ///< dotted key, e.g. "shell.inner_radius_m"
  std::string message;
};

/// The supported physical range of one numeric key, and the range typical scenarios use (only
/// for naming the likely cause when the solver fails). Documented in docs/simulate.md.
struct KeyRange {
  const char* key;
  double (*value)(const Scenario&);  ///< the quantity checked (the key itself, or a ratio)
  double (*raw)(const Scenario&);    ///< the key's own value when `value` is a ratio, else null
  bool (*applies)(const Scenario&);
  double lo, hi;                  ///< allowed, inclusive
  double typical_lo, typical_hi;  ///< what the shipped scenarios and the literature use
  bool decades;                   ///< distance from typical in decades (else in units of 100 K)
  const char* unit;
  const char* why;
};

constexpr double kAbsoluteZeroC = -273.15;

bool always(const Scenario&) {
  return true;
}
double inner_m(const Scenario& s) {
  return s.inner_radius_m;
}
bool has_core(const Scenario& s) {
  return s.inner_radius_m > 0;
}
bool has_ice(const Scenario& s) {
  return s.outer_radius_m > s.inner_radius_m;
}
bool held_inner(const Scenario& s) {
  return s.inner_kind == InnerBoundary::temperature;
}
bool uses_outer_temperature(const Scenario& s) {
  return s.outer_kind == OuterBoundary::temperature || s.outer_kind == OuterBoundary::convective;
}
bool convective(const Scenario& s) {
  return s.outer_kind == OuterBoundary::convective;
}
bool flux(const Scenario& s) {
  return s.outer_kind == OuterBoundary::flux;
}

/// Sizes: 0.1 mm to 100 m (a continuum heat-conduction model of a hand-sized object; below
/// 0.1 mm surface effects and above 100 m gravity-driven flow dominate). A core or an ice layer
/// thinner than 1e-4 of the outer radius is 100 times the solver's remnant size (1e-6 b0), the
/// least that still resolves it on 4+ cells. Temperatures: not below absolute zero; liquid water
/// at 1 atm below 100 C (boiling is not modelled); air up to 1000 C (a flame). Heat transfer
/// coefficients up to 1e5 W/(m^2 K), the top of the boiling/condensation range (Incropera et
/// al., Fundamentals of Heat and Mass Transfer, 7th ed., Table 1.1); fluxes up to 1e7 W/m^2
/// (a solar furnace). Materials within the span of real solids and liquids.
const std::vector<KeyRange>& key_ranges() {
  static const std::vector<KeyRange> ranges = {
      {"shell.outer_radius_m", [](const Scenario& s) { return s.outer_radius_m; }, nullptr, always,
       1e-4, 100, 1e-3, 1, true, "m", "a hand-sized continuum object"},
      {"shell.inner_radius_m",
       [](const Scenario& s) { return s.inner_radius_m / s.outer_radius_m; }, inner_m, has_core,
       1e-4, 1, 0.05, 1, true, "x outer_radius_m",
       "a core thinner than 1e-4 of the shell is below the solver's resolution"},
      {"shell.inner_radius_m",
       [](const Scenario& s) { return 1 - s.inner_radius_m / s.outer_radius_m; }, inner_m, has_ice,
       1e-4, 1, 0.05, 1, true, "x outer_radius_m of ice thickness",
       "an ice layer thinner than 1e-4 of the shell is below the solver's resolution"},
      {"water.initial_temperature_c",
       [](const Scenario& s) { return s.water_initial_temperature_c; }, nullptr, has_core,
       kAbsoluteZeroC, 100, 0, 40, false, "C", "liquid water boils at 100 C (not modelled)"},
      {"ice.initial_temperature_c", [](const Scenario& s) { return s.ice_initial_temperature_c; },
       nullptr, has_ice, kAbsoluteZeroC, 100, -40, 0, false, "C",
       "nothing is colder than absolute zero"},
      {"inner_boundary.temperature_c", [](const Scenario& s) { return s.inner_temperature_c; },
       nullptr, held_inner, kAbsoluteZeroC, 100, 0, 60, false, "C",
       "water at the wall boils at 100 C (not modelled)"},
      {"outer_boundary.temperature_c", [](const Scenario& s) { return s.outer_temperature_c; },
       nullptr, uses_outer_temperature, kAbsoluteZeroC, 1000, -40, 60, false, "C",
       "air from absolute zero to a flame"},
      {"outer_boundary.heat_transfer_coefficient_w_m2k",
       [](const Scenario& s) { return s.heat_transfer_coefficient_w_m2k; }, nullptr, convective,
       1e-3, 1e5, 2, 1000, true, "W/(m^2 K)",
       "free convection to boiling water (Incropera Table 1.1)"},
      {"outer_boundary.flux_w_m2", [](const Scenario& s) { return std::abs(s.flux_w_m2); }, nullptr,
       flux, 0, 1e7, 0, 1e4, true, "W/m^2 (absolute)", "up to a solar furnace"},
      {"materials.ice_conductivity_w_mk",
       [](const Scenario& s) { return s.materials.ice_conductivity_w_mk; }, nullptr, always, 1e-3,
       1e4, 0.1, 10, true, "W/(m K)", "aerogel to diamond"},
      {"materials.water_conductivity_w_mk",
       [](const Scenario& s) { return s.materials.water_conductivity_w_mk; }, nullptr, always, 1e-3,
       1e4, 0.1, 10, true, "W/(m K)", "aerogel to diamond"},
      {"materials.ice_density_kg_m3",
       [](const Scenario& s) { return s.materials.ice_density_kg_m3; }, nullptr, always, 1, 1e5,
       500, 2000, true, "kg/m^3", "real solids and liquids"},
      {"materials.water_density_kg_m3",
       [](const Scenario& s) { return s.materials.water_density_kg_m3; }, nullptr, always, 1, 1e5,
       500, 2000, true, "kg/m^3", "real solids and liquids"},
      {"materials.ice_specific_heat_j_kgk",
       [](const Scenario& s) { return s.materials.ice_specific_heat_j_kgk; }, nullptr, always, 10,
       1e5, 500, 5000, true, "J/(kg K)", "real solids and liquids"},
      {"materials.water_specific_heat_j_kgk",
       [](const Scenario& s) { return s.materials.water_specific_heat_j_kgk; }, nullptr, always, 10,
       1e5, 500, 5000, true, "J/(kg K)", "real solids and liquids"},
      {"materials.latent_heat_j_kg", [](const Scenario& s) { return s.materials.latent_heat_j_kg; },
       nullptr, always, 100, 1e7, 1e4, 1e6, true, "J/kg", "real solids"},
      {"materials.melting_point_c", [](const Scenario& s) { return s.materials.melting_point_c; },
       nullptr, always, kAbsoluteZeroC, 100, -10, 10, false, "C",
       "below the boiling point of water"},
  };
  return ranges;
}

/// How far v lies outside [lo, hi]: in decades, or in units of 100 K for temperatures.
double distance_outside(const KeyRange& r, double v) {
  if (!r.decades) return std::max({0.0, r.typical_lo - v, v - r.typical_hi}) / 100.0;
  if (!(v > 0)) return r.typical_lo > 0 ? 1.0 : 0.0;
  const double lv = std::log10(v);
  return std::max({0.0, (r.typical_lo > 0 ? std::log10(r.typical_lo) : lv) - lv,
                   lv - std::log10(r.typical_hi)});
}

std::optional<Problem> outside_range(const Scenario& s) {
  for (const KeyRange& r : key_ranges()) {
    if (!r.applies(s)) continue;
    const double v = r.value(s);
    if (v >= r.lo && v <= r.hi) continue;
    const std::string shown = r.raw ? num(r.raw(s)) + " m, i.e. " : "";
    return Problem{r.key, "(" + shown + num(v) + " " + r.unit +
                              ") is outside the supported range [" + num(r.lo) + ", " + num(r.hi) +
                              "] " + r.unit + ": " + r.why + " (see docs/simulate.md)"};
  }
  return std::nullopt;
}

/// The physics rules every scenario must satisfy, shared by the parser and validate_scenario.
std::optional<Problem> find_problem(const Scenario& s) {
  const Materials& m = s.materials;
  const double tm = m.melting_point_c;
  const std::pair<const char*, double> positive_materials[] = {
      {"materials.ice_conductivity_w_mk", m.ice_conductivity_w_mk},
      {"materials.ice_density_kg_m3", m.ice_density_kg_m3},
      {"materials.ice_specific_heat_j_kgk", m.ice_specific_heat_j_kgk},
      {"materials.water_conductivity_w_mk", m.water_conductivity_w_mk},
      {"materials.water_density_kg_m3", m.water_density_kg_m3},
      {"materials.water_specific_heat_j_kgk", m.water_specific_heat_j_kgk},
      {"materials.latent_heat_j_kg", m.latent_heat_j_kg}};
  const std::pair<const char*, double> finite[] = {
      {"simulation.duration_s", s.duration_s},
      {"simulation.output_interval_s", s.output_interval_s},
      {"simulation.time_tolerance", s.time_tolerance},
      {"shell.inner_radius_m", s.inner_radius_m},
      {"shell.outer_radius_m", s.outer_radius_m},
      {"shell.length_m", s.length_m},
      {"shell.lateral_size_m", s.lateral_size_m},
      {"water.initial_temperature_c", s.water_initial_temperature_c},
      {"ice.initial_temperature_c", s.ice_initial_temperature_c},
      {"inner_boundary.temperature_c", s.inner_temperature_c},
      {"outer_boundary.temperature_c", s.outer_temperature_c},
      {"outer_boundary.heat_transfer_coefficient_w_m2k", s.heat_transfer_coefficient_w_m2k},
      {"outer_boundary.flux_w_m2", s.flux_w_m2},
      {"materials.melting_point_c", tm}};
  for (auto [key, v] : finite)
    if (!std::isfinite(v)) return Problem{key, "must be a finite number (got " + num(v) + ")"};
  for (auto [key, v] : positive_materials)
    if (!(v > 0) || !std::isfinite(v)) return Problem{key, "must be positive (got " + num(v) + ")"};
  if (!(s.duration_s > 0))
    return Problem{"simulation.duration_s", "must be positive (got " + num(s.duration_s) + ")"};
  if (!(s.output_interval_s > 0))
    return Problem{"simulation.output_interval_s",
                   "must be positive (got " + num(s.output_interval_s) + ")"};
  if (s.output_interval_s > s.duration_s)
    return Problem{"simulation.output_interval_s",
                   "(" + num(s.output_interval_s) +
                       " s) is longer than the run (duration_s = " + num(s.duration_s) + " s)"};
  if (s.duration_s / s.output_interval_s > 1e6)
    return Problem{"simulation.output_interval_s",
                   "gives more than 10^6 output rows; use a longer interval"};
  if (s.cells_per_phase < 4 || s.cells_per_phase > 100000)
    return Problem{"simulation.cells_per_phase",
                   "must be between 4 and 100000 (got " + std::to_string(s.cells_per_phase) + ")"};
  if (!(s.time_tolerance > 0 && s.time_tolerance <= 1e-2))
    return Problem{"simulation.time_tolerance",
                   "must be in (0, 0.01] (got " + num(s.time_tolerance) + ")"};
  if (!(s.inner_radius_m >= 0))
    return Problem{"shell.inner_radius_m",
                   "must not be negative (got " + num(s.inner_radius_m) + ")"};
  if (!(s.outer_radius_m > 0))
    return Problem{"shell.outer_radius_m", "must be positive (got " + num(s.outer_radius_m) + ")"};
  if (s.inner_radius_m > s.outer_radius_m)
    return Problem{"shell.inner_radius_m", "(" + num(s.inner_radius_m) +
                                               " m) is larger than outer_radius_m (" +
                                               num(s.outer_radius_m) + " m)"};
  if (!(s.length_m > 0))
    return Problem{"shell.length_m", "must be positive (got " + num(s.length_m) + ")"};
  if (!(s.lateral_size_m > 0))
    return Problem{"shell.lateral_size_m", "must be positive (got " + num(s.lateral_size_m) + ")"};
  if (s.inner_radius_m > 0 && s.water_initial_temperature_c < tm)
    return Problem{"water.initial_temperature_c",
                   "(" + num(s.water_initial_temperature_c) +
                       " C) is below the melting point: supercooled water is not modelled"};
  if (s.outer_radius_m > s.inner_radius_m && s.ice_initial_temperature_c > tm)
    return Problem{"ice.initial_temperature_c",
                   "(" + num(s.ice_initial_temperature_c) + " C) is above the melting point"};
  if (s.geometry != Geometry::planar && s.inner_kind != InnerBoundary::symmetry)
    return Problem{"inner_boundary.kind", "a held inner temperature needs geometry = \"planar\""};
  if (s.inner_kind == InnerBoundary::temperature && s.inner_temperature_c < tm)
    return Problem{
        "inner_boundary.temperature_c",
        "(" + num(s.inner_temperature_c) +
            " C) is below the melting point: water would freeze onto the wall (not modelled)"};
  if (s.outer_kind == OuterBoundary::temperature && s.outer_temperature_c > tm)
    return Problem{"outer_boundary.temperature_c",
                   "(" + num(s.outer_temperature_c) +
                       " C) is above the melting point: a held temperature above melting on a "
                       "draining surface is ill-posed (use kind = \"convective\" or \"flux\")"};
  if (s.outer_kind == OuterBoundary::convective && !(s.heat_transfer_coefficient_w_m2k > 0))
    return Problem{"outer_boundary.heat_transfer_coefficient_w_m2k",
                   "must be positive (got " + num(s.heat_transfer_coefficient_w_m2k) + ")"};
  if (auto p = outside_range(s)) return p;
  if (s.inner_radius_m == s.outer_radius_m) {
    // No ice yet: it must start freezing at once.
    const bool water_at_melting = s.water_initial_temperature_c == tm;
    const bool freezes =
        (s.outer_kind == OuterBoundary::temperature && s.outer_temperature_c < tm) ||
        (s.outer_kind == OuterBoundary::convective && s.outer_temperature_c < tm &&
         water_at_melting) ||
        (s.outer_kind == OuterBoundary::flux && s.flux_w_m2 < 0 && water_at_melting);
    if (!freezes)
      return Problem{"shell.outer_radius_m",
                     "equals inner_radius_m (no ice at t = 0), so the outer boundary must freeze "
                     "the water at once: "
                     "a held temperature below melting, or convective/flux cooling of water at the "
                     "melting point"};
  }
  // Grid runs ([shape]); the [shell] rules above pass on its unused defaults.
  if (auto p = find_grid_problem(s)) return Problem{p->key, p->message};
  return std::nullopt;
}

/// Throws the problem through the TOML table (with the key's line) when the key is in the file.
[[noreturn]] void fail_in_table(const TomlTable& root, const Problem& p) {
  const auto dot = p.key.find('.');
  const std::string table = p.key.substr(0, dot), key = p.key.substr(dot + 1);
  if (auto t = root.optional_table(table); t && t->has(key)) t->fail(key, p.message);
  if (auto t = root.optional_table(table)) t->fail(key, p.message);
  throw UserError(root.source_name(), "key '" + p.key + "'", p.message);
}

void reject_unless(const TomlTable& t, const std::string& key, bool allowed,
                   const std::string& why) {
  if (!allowed && t.has(key)) t.fail(key, why);
}

/// Unknown tables and keys are reported before anything else: a misspelt key would otherwise
/// surface as "required key is missing" for the key it was meant to be.
void check_schema(const TomlTable& root, const std::set<std::string>& foreign_sections) {
  static const std::vector<std::pair<std::string, std::vector<std::string>>> schema = {
      {"simulation",
       {"geometry", "duration_s", "output_interval_s", "cells_per_phase", "time_tolerance",
        "cell_size_m", "max_step_s"}},
      {"shape", {"outer", "cavity"}},
      {"shell", {"inner_radius_m", "outer_radius_m", "length_m", "lateral_size_m"}},
      {"water", {"initial_temperature_c"}},
      {"ice", {"initial_temperature_c"}},
      {"inner_boundary", {"kind", "temperature_c"}},
      {"outer_boundary", {"kind", "temperature_c", "heat_transfer_coefficient_w_m2k", "flux_w_m2"}},
      {"materials",
       {"ice_conductivity_w_mk", "ice_density_kg_m3", "ice_specific_heat_j_kgk",
        "water_conductivity_w_mk", "water_density_kg_m3", "water_specific_heat_j_kgk",
        "latent_heat_j_kg", "melting_point_c"}}};
  for (const std::string& name : root.keys()) {
    if (foreign_sections.count(name)) continue;
    const auto it =
        std::find_if(schema.begin(), schema.end(), [&](const auto& e) { return e.first == name; });
    if (it == schema.end()) root.fail(name, "unknown key");
    const auto table = root.optional_table(name);  // throws "expected a table" for a plain key
    for (const std::string& key : table->keys())
      if (std::find(it->second.begin(), it->second.end(), key) == it->second.end())
        table->fail(key, "unknown key");
  }
}

/// One shape of [shape] (an inline table); `dir` resolves a relative OBJ path.
ShapeSpec parse_shape_spec(const TomlTable& t, const std::filesystem::path& dir) {
  ShapeSpec s;
  const std::string kind = t.get_string("kind");
  static const std::vector<std::pair<std::string, std::vector<std::string>>> keys = {
      {"box", {"size_m", "edge_radius_m"}},
      {"sphere", {"radius_m"}},
      {"cylinder", {"radius_m", "height_m"}},
      {"obj", {"file", "scale", "translate_m"}}};
  const auto it =
      std::find_if(keys.begin(), keys.end(), [&](const auto& e) { return e.first == kind; });
  if (it == keys.end())
    t.fail("kind", "unknown kind '" + kind + "' (expected box, sphere, cylinder or obj)");
  for (const std::string& key : t.keys())
    if (key != "kind" && key != "center_m" &&
        std::find(it->second.begin(), it->second.end(), key) == it->second.end())
      t.fail(
          key, "unknown key for kind = \"" + kind + "\" (expected " + [&] {
            std::string list = "center_m";
            for (const auto& k : it->second) list += ", " + k;
            return list;
          }() + ")");
  s.center_m = t.get_vec3("center_m", s.center_m);
  if (kind == "box") {
    s.kind = ShapeKind::box;
    s.size_m = t.get_vec3("size_m");
    s.edge_radius_m = t.get_double("edge_radius_m", 0.0);
  } else if (kind == "sphere") {
    s.kind = ShapeKind::sphere;
    s.radius_m = t.get_double("radius_m");
  } else if (kind == "cylinder") {
    s.kind = ShapeKind::cylinder;
    s.radius_m = t.get_double("radius_m");
    s.height_m = t.get_double("height_m");
  } else {
    s.kind = ShapeKind::obj;
    const std::filesystem::path file = t.get_string("file");
    s.file = (file.is_relative() ? dir / file : file).lexically_normal().string();
    s.scale = t.get_double("scale", 1.0);
    s.translate_m = t.get_vec3("translate_m", s.translate_m);
  }
  return s;
}

Shape parse_shape(const TomlTable& t) {
  // relative OBJ paths are relative to the scenario file's folder
  const std::filesystem::path source = t.source_name();
  const std::filesystem::path dir =
      std::filesystem::is_regular_file(source) ? source.parent_path() : std::filesystem::path{};
  Shape shape;
  shape.outer = parse_shape_spec(t.table("outer"), dir);
  if (auto cavity = t.optional_table("cavity")) shape.cavity = parse_shape_spec(*cavity, dir);
  return shape;
}

Materials parse_materials(const TomlTable& t, Materials m) {
  m.ice_conductivity_w_mk = t.get_double("ice_conductivity_w_mk", m.ice_conductivity_w_mk);
  m.ice_density_kg_m3 = t.get_double("ice_density_kg_m3", m.ice_density_kg_m3);
  m.ice_specific_heat_j_kgk = t.get_double("ice_specific_heat_j_kgk", m.ice_specific_heat_j_kgk);
  m.water_conductivity_w_mk = t.get_double("water_conductivity_w_mk", m.water_conductivity_w_mk);
  m.water_density_kg_m3 = t.get_double("water_density_kg_m3", m.water_density_kg_m3);
  m.water_specific_heat_j_kgk =
      t.get_double("water_specific_heat_j_kgk", m.water_specific_heat_j_kgk);
  m.latent_heat_j_kg = t.get_double("latent_heat_j_kg", m.latent_heat_j_kg);
  m.melting_point_c = t.get_double("melting_point_c", m.melting_point_c);
  return m;
}

}  // namespace

Materials default_materials() {
  static const Materials m = [] {
    const TomlTable t = TomlTable::parse_string(std::string(kIceWaterMaterialsToml),
                                                "<built-in data/materials/ice_water.toml>");
    Materials out = parse_materials(t, Materials{});
    // every key of the data file is required: a renamed key must not fall back silently
    for (const char* key : {"ice_conductivity_w_mk", "ice_density_kg_m3", "ice_specific_heat_j_kgk",
                            "water_conductivity_w_mk", "water_density_kg_m3",
                            "water_specific_heat_j_kgk", "latent_heat_j_kg", "melting_point_c"})
      if (!t.has(key)) t.fail(key, "missing from the built-in material table");
    t.check_no_unknown_keys();
    return out;
  }();
  return m;
}

std::string default_scenario_text() {
  return std::string(kDefaultScenarioToml);
}

Scenario default_scenario() {
  // The built-in scenario also drives `thaw run`, whose sections src/pipeline checks.
  return parse_scenario(
      TomlTable::parse_string(default_scenario_text(), "<built-in data/scenarios/default.toml>"),
      other_stage_tables());
}

/// Top-level tables of a scenario file that belong to later stages of `thaw run` (film,
/// meshing, rendering): `thaw simulate` skips them, unread, so their owner still reports
/// their unknown keys with its own check.
const std::set<std::string>& other_stage_tables() {
  static const std::set<std::string> tables = {"film", "mesh", "render"};
  return tables;
}

Scenario parse_scenario(const TomlTable& root) {
  return parse_scenario(root, other_stage_tables());
}

Scenario parse_scenario(const TomlTable& root, const std::set<std::string>& foreign_sections) {
  Scenario s;
  s.source_name = root.source_name();
  s.materials = default_materials();
  check_schema(root, foreign_sections);

  const TomlTable sim = root.table("simulation");
  const std::string geometry = sim.get_string("geometry");
  if (geometry == "axisymmetric")
    s.grid = GridGeometry::axisymmetric;
  else if (geometry == "3d")
    s.grid = GridGeometry::cartesian3d;
  else if (!parse_geometry(geometry, s.geometry))
    sim.fail("geometry", "unknown geometry '" + geometry +
                             "' (expected planar, cylinder, sphere, axisymmetric or 3d)");
  const bool grid = s.grid != GridGeometry::none;
  s.duration_s = sim.get_double("duration_s");
  s.output_interval_s = sim.get_double("output_interval_s");
  reject_unless(sim, "cells_per_phase", !grid,
                "only used by the 1D geometries (grid runs: cell_size_m)");
  reject_unless(sim, "time_tolerance", !grid,
                "only used by the 1D geometries (grid runs: max_step_s)");
  reject_unless(sim, "cell_size_m", grid, "only used with geometry = \"axisymmetric\" or \"3d\"");
  reject_unless(sim, "max_step_s", grid, "only used with geometry = \"axisymmetric\" or \"3d\"");
  const std::int64_t cells = sim.get_int("cells_per_phase", s.cells_per_phase);
  if (cells < 4 || cells > 100000)
    sim.fail("cells_per_phase", "must be between 4 and 100000 (got " + std::to_string(cells) + ")");
  s.cells_per_phase = static_cast<int>(cells);
  s.time_tolerance = sim.get_double("time_tolerance", s.time_tolerance);
  if (grid) {
    if (sim.has("cell_size_m"))
      s.cell_size_m = sim.require_positive("cell_size_m", sim.get_double("cell_size_m"));
    s.max_step_s = sim.require_positive("max_step_s", sim.get_double("max_step_s", s.max_step_s));
    if (root.has("shell"))
      root.fail("shell", "[shell] describes the 1D geometries; geometry = \"" + geometry +
                             "\" takes [shape]");
    s.shape = parse_shape(root.table("shape"));
  } else {
    if (root.has("shape"))
      root.fail(
          "shape",
          "only used with geometry = \"axisymmetric\" or \"3d\" (the 1D geometries take [shell])");
    const TomlTable shell = root.table("shell");
    s.inner_radius_m = shell.get_double("inner_radius_m");
    s.outer_radius_m = shell.get_double("outer_radius_m");
    reject_unless(shell, "length_m", s.geometry == Geometry::cylinder,
                  "only used with geometry = \"cylinder\"");
    reject_unless(shell, "lateral_size_m", s.geometry == Geometry::planar,
                  "only used with geometry = \"planar\"");
    // Defaults sized to the shell so that a default capsule or slab looks like one.
    s.length_m = shell.get_double("length_m", 2.0 * s.outer_radius_m);
    s.lateral_size_m = shell.get_double("lateral_size_m", 4.0 * s.outer_radius_m);
  }

  if (!grid || s.shape.cavity || root.has("water"))
    s.water_initial_temperature_c = root.table("water").get_double("initial_temperature_c");
  s.ice_initial_temperature_c = root.table("ice").get_double("initial_temperature_c");

  if (auto inner = root.optional_table("inner_boundary")) {
    if (s.geometry != Geometry::planar)
      root.fail("inner_boundary",
                "only for geometry = \"planar\" (curved shells have a symmetric centre)");
    const std::string kind = inner->get_string("kind");
    if (kind == "symmetry") {
      s.inner_kind = InnerBoundary::symmetry;
    } else if (kind == "temperature") {
      s.inner_kind = InnerBoundary::temperature;
      s.inner_temperature_c = inner->get_double("temperature_c");
    } else {
      inner->fail("kind",
                  "unknown inner boundary '" + kind + "' (expected symmetry or temperature)");
    }
    reject_unless(*inner, "temperature_c", s.inner_kind == InnerBoundary::temperature,
                  "only used with kind = \"temperature\"");
  }

  const TomlTable outer = root.table("outer_boundary");
  const std::string kind = outer.get_string("kind");
  if (kind == "temperature")
    s.outer_kind = OuterBoundary::temperature;
  else if (kind == "convective")
    s.outer_kind = OuterBoundary::convective;
  else if (kind == "flux")
    s.outer_kind = OuterBoundary::flux;
  else if (kind == "insulated")
    s.outer_kind = OuterBoundary::insulated;
  else
    outer.fail("kind", "unknown outer boundary '" + kind +
                           "' (expected temperature, convective, flux or insulated)");
  const bool uses_t =
      s.outer_kind == OuterBoundary::temperature || s.outer_kind == OuterBoundary::convective;
  reject_unless(outer, "temperature_c", uses_t, "not used with kind = \"" + kind + "\"");
  reject_unless(outer, "heat_transfer_coefficient_w_m2k", s.outer_kind == OuterBoundary::convective,
                "only used with kind = \"convective\"");
  reject_unless(outer, "flux_w_m2", s.outer_kind == OuterBoundary::flux,
                "only used with kind = \"flux\"");
  s.outer_temperature_c = uses_t ? outer.get_double("temperature_c") : s.materials.melting_point_c;
  s.heat_transfer_coefficient_w_m2k = s.outer_kind == OuterBoundary::convective
                                          ? outer.get_double("heat_transfer_coefficient_w_m2k")
                                          : 0.0;
  s.flux_w_m2 = s.outer_kind == OuterBoundary::flux ? outer.get_double("flux_w_m2") : 0.0;

  if (auto mat = root.optional_table("materials")) s.materials = parse_materials(*mat, s.materials);
  if (s.inner_kind == InnerBoundary::symmetry) s.inner_temperature_c = s.materials.melting_point_c;
  if (!uses_t) s.outer_temperature_c = s.materials.melting_point_c;

  // check_schema() has already rejected every unknown key outside the foreign sections.
  if (foreign_sections.empty()) root.check_no_unknown_keys();
  if (auto p = find_problem(s)) fail_in_table(root, *p);
  return s;
}

Scenario parse_scenario_string(const std::string& text, const std::string& source_name) {
  return parse_scenario(TomlTable::parse_string(text, source_name));
}

Scenario read_scenario_file(const std::filesystem::path& path) {
  return parse_scenario(TomlTable::parse_file(path));
}

LikelyCause likely_cause_of_solver_failure(const Scenario& s) {
  const KeyRange* worst = nullptr;
  double worst_distance = 0;
  for (const KeyRange& r : key_ranges()) {
    if (!r.applies(s)) continue;
    const double d = distance_outside(r, r.value(s));
    if (d > worst_distance) worst = &r, worst_distance = d;
  }
  if (!worst)
    return {"simulation.time_tolerance",
            "every value is in its typical range; try a looser simulation.time_tolerance (now " +
                num(s.time_tolerance) + ") or fewer simulation.cells_per_phase (now " +
                std::to_string(s.cells_per_phase) + ")"};
  const double v = worst->raw ? worst->raw(s) : worst->value(s);
  const std::string typical = worst->raw ? ""
                                         : " (typical: " + num(worst->typical_lo) + " to " +
                                               num(worst->typical_hi) + " " + worst->unit + ")";
  return {worst->key, "its value " + num(v) + " is the farthest from typical scenarios" + typical +
                          "; try a less extreme value"};
}

void validate_scenario(const Scenario& scenario, const std::string& source_name) {
  if (auto p = find_problem(scenario))
    throw UserError(source_name.empty() ? scenario.source_name : source_name,
                    "key '" + p->key + "'", p->message);
}

nlohmann::json scenario_to_json(const Scenario& s) {
  nlohmann::json j;
  j["simulation"] = {{"geometry", to_string(s.geometry)},
                     {"duration_s", s.duration_s},
                     {"output_interval_s", s.output_interval_s},
                     {"cells_per_phase", s.cells_per_phase},
                     {"time_tolerance", s.time_tolerance}};
  j["shell"] = {{"inner_radius_m", s.inner_radius_m},
                {"outer_radius_m", s.outer_radius_m},
                {"length_m", s.length_m},
                {"lateral_size_m", s.lateral_size_m}};
  if (s.grid != GridGeometry::none) {
    j["simulation"] = {{"geometry", to_string(s.grid)},
                       {"duration_s", s.duration_s},
                       {"output_interval_s", s.output_interval_s},
                       {"cell_size_m", effective_cell_size_m(s)},
                       {"max_step_s", s.max_step_s}};
    j.erase("shell");
    auto shape_json = [](const ShapeSpec& sp) {
      nlohmann::json o = {{"kind", to_string(sp.kind)}, {"center_m", sp.center_m}};
      switch (sp.kind) {
        case ShapeKind::box:
          o["size_m"] = sp.size_m, o["edge_radius_m"] = sp.edge_radius_m;
          break;
        case ShapeKind::sphere:
          o["radius_m"] = sp.radius_m;
          break;
        case ShapeKind::cylinder:
          o["radius_m"] = sp.radius_m, o["height_m"] = sp.height_m;
          break;
        case ShapeKind::obj:
          o["file"] = sp.file, o["scale"] = sp.scale, o["translate_m"] = sp.translate_m;
          break;
      }
      return o;
    };
    j["shape"]["outer"] = shape_json(s.shape.outer);
    if (s.shape.cavity) j["shape"]["cavity"] = shape_json(*s.shape.cavity);
  }
  j["water"] = {{"initial_temperature_c", s.water_initial_temperature_c}};
  j["ice"] = {{"initial_temperature_c", s.ice_initial_temperature_c}};
  j["inner_boundary"] = {{"kind", to_string(s.inner_kind)}};
  if (s.inner_kind == InnerBoundary::temperature)
    j["inner_boundary"]["temperature_c"] = s.inner_temperature_c;
  nlohmann::json outer = {{"kind", to_string(s.outer_kind)}};
  if (s.outer_kind == OuterBoundary::temperature || s.outer_kind == OuterBoundary::convective)
    outer["temperature_c"] = s.outer_temperature_c;
  if (s.outer_kind == OuterBoundary::convective)
    outer["heat_transfer_coefficient_w_m2k"] = s.heat_transfer_coefficient_w_m2k;
  if (s.outer_kind == OuterBoundary::flux) outer["flux_w_m2"] = s.flux_w_m2;
  j["outer_boundary"] = outer;
  const Materials& m = s.materials;
  j["materials"] = {{"ice_conductivity_w_mk", m.ice_conductivity_w_mk},
                    {"ice_density_kg_m3", m.ice_density_kg_m3},
                    {"ice_specific_heat_j_kgk", m.ice_specific_heat_j_kgk},
                    {"water_conductivity_w_mk", m.water_conductivity_w_mk},
                    {"water_density_kg_m3", m.water_density_kg_m3},
                    {"water_specific_heat_j_kgk", m.water_specific_heat_j_kgk},
                    {"latent_heat_j_kg", m.latent_heat_j_kg},
                    {"melting_point_c", m.melting_point_c}};
  return j;
}

}  // namespace thaw::sim
