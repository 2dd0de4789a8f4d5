#include "sim/scenario/scenario_rules.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include "base/error.h"
#include "base/number_text.h"
#include "sim/boundary/scenario_air.h"
#include "sim/grid/body_faces.h"
#include "sim/grid/grid_rules.h"
#include "sim/scenario/materials_keys.h"

// GCC 12 reports a false -Wrestrict inside std::string's operator+(const char*, string&&) once
// these messages are inlined into one function (GCC bug 105651, fixed in GCC 13).
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ == 12
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

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
    case OuterBoundary::air:
      return "air";
  }
  return "?";
}

namespace {

/// Numbers in messages: the shortest text that reads back as the same double.
std::string num(double v) {
  return shortest_text(v);
}

/// The supported physical range of one numeric key, and the range typical scenarios use (only
/// for naming the likely cause when the solver fails). Documented in docs/simulate.md.
struct KeyRange {
  std::string key;
  std::function<double(const Scenario&)> value;  ///< the quantity checked (the key, or a ratio)
  double (*raw)(const Scenario&);  ///< the key's own value when `value` is a ratio, else null
  bool (*applies)(const Scenario&);
  double lo, hi;                  ///< allowed, inclusive
  double typical_lo, typical_hi;  ///< what the shipped scenarios and the literature use
  bool decades;                   ///< distance from typical in decades (else in units of 100 K)
  std::string unit;
  std::string why;
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
  return s.outer_kind == OuterBoundary::temperature || s.outer_kind == OuterBoundary::convective ||
         s.outer_kind == OuterBoundary::air;
}
bool cylinder(const Scenario& s) {
  return s.grid == GridGeometry::none && s.geometry == Geometry::cylinder;
}
bool planar(const Scenario& s) {
  return s.grid == GridGeometry::none && s.geometry == Geometry::planar;
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
  static const std::vector<KeyRange> ranges = [] {
    std::vector<KeyRange> out = {
        {"shell.outer_radius_m", [](const Scenario& s) { return s.outer_radius_m; }, nullptr,
         always, 1e-4, 100, 1e-3, 1, true, "m", "a hand-sized continuum object"},
        // After outer_radius_m, whose multiples they default to (a huge outer radius is named,
        // not the infinite length derived from it).
        {"shell.length_m", [](const Scenario& s) { return s.length_m; }, nullptr, cylinder, 1e-4,
         100, 1e-3, 1, true, "m", "a hand-sized continuum object"},
        {"shell.lateral_size_m", [](const Scenario& s) { return s.lateral_size_m; }, nullptr,
         planar, 1e-4, 100, 1e-3, 1, true, "m", "a hand-sized continuum object"},
        {"shell.inner_radius_m",
         [](const Scenario& s) { return s.inner_radius_m / s.outer_radius_m; }, inner_m, has_core,
         1e-4, 1, 0.05, 1, true, "x outer_radius_m",
         "a core thinner than 1e-4 of the shell is below the solver's resolution"},
        {"shell.inner_radius_m",
         [](const Scenario& s) { return 1 - s.inner_radius_m / s.outer_radius_m; }, inner_m,
         has_ice, 1e-4, 1, 0.05, 1, true, "x outer_radius_m of ice thickness",
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
        {"outer_boundary.flux_w_m2", [](const Scenario& s) { return std::abs(s.flux_w_m2); },
         nullptr, flux, 0, 1e7, 0, 1e4, true, "W/m^2 (absolute)", "up to a solar furnace"},
    };
    // [materials]: the properties of its key table (sim/scenario/materials_keys.h), in table order
    for (const MaterialsKey& row : materials_keys()) {
      if (row.extra.flow) continue;
      const auto field = std::get<NumberKey<Materials>>(row.value).field;
      out.push_back({"materials." + std::string(row.name),
                     [field](const Scenario& s) { return s.materials.*field; }, nullptr, always,
                     row.extra.lo, row.extra.hi, row.extra.typical_lo, row.extra.typical_hi,
                     row.extra.decades, std::string(row.unit), std::string(row.extra.why)});
    }
    return out;
  }();
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

std::optional<ScenarioProblem> outside_range(const Scenario& s) {
  for (const KeyRange& r : key_ranges()) {
    if (!r.applies(s)) continue;
    const double v = r.value(s);
    if (v >= r.lo && v <= r.hi) continue;
    const std::string shown = r.raw ? num(r.raw(s)) + " m, i.e. " : "";
    return ScenarioProblem{r.key, "(" + shown + num(v) + " " + r.unit +
                                      ") is outside the supported range [" + num(r.lo) + ", " +
                                      num(r.hi) + "] " + r.unit + ": " + r.why +
                                      " (see docs/simulate.md)"};
  }
  return std::nullopt;
}

/// Every number finite; the materials' properties positive.
std::optional<ScenarioProblem> number_problem(const Scenario& s) {
  // [materials]: every property finite (after the other keys), and positive where its supported
  // range is (all but the melting point), in table order
  std::vector<std::pair<std::string, double>> finite_materials, positive_materials;
  for (const MaterialsKey& row : materials_keys()) {
    if (row.extra.flow) continue;
    const double v = s.materials.*(std::get<NumberKey<Materials>>(row.value).field);
    (row.extra.lo > 0 ? positive_materials : finite_materials)
        .emplace_back("materials." + std::string(row.name), v);
  }
  const std::pair<const char*, double> finite[] = {
      {"simulation.duration_s", s.duration_s},
      {"simulation.output_interval_s", s.output_interval_s},
      {"simulation.time_tolerance", s.time_tolerance},
      {"shell.inner_radius_m", s.inner_radius_m},
      {"shell.outer_radius_m", s.outer_radius_m},
      {"water.initial_temperature_c", s.water_initial_temperature_c},
      {"ice.initial_temperature_c", s.ice_initial_temperature_c},
      {"inner_boundary.temperature_c", s.inner_temperature_c},
      {"outer_boundary.temperature_c", s.outer_temperature_c},
      {"outer_boundary.heat_transfer_coefficient_w_m2k", s.heat_transfer_coefficient_w_m2k},
      {"outer_boundary.flux_w_m2", s.flux_w_m2}};
  for (auto [key, v] : finite)
    if (!std::isfinite(v))
      return ScenarioProblem{key, "must be a finite number (got " + num(v) + ")"};
  for (const auto& [key, v] : finite_materials)
    if (!std::isfinite(v))
      return ScenarioProblem{key, "must be a finite number (got " + num(v) + ")"};
  for (const auto& [key, v] : positive_materials)
    if (!(v > 0) || !std::isfinite(v))
      return ScenarioProblem{key, "must be positive (got " + num(v) + ")"};
  return std::nullopt;
}

/// [simulation]: duration, output interval, cells, tolerance.
std::optional<ScenarioProblem> simulation_problem(const Scenario& s) {
  if (!(s.duration_s > 0))
    return ScenarioProblem{"simulation.duration_s",
                           "must be positive (got " + num(s.duration_s) + ")"};
  if (!(s.output_interval_s > 0))
    return ScenarioProblem{"simulation.output_interval_s",
                           "must be positive (got " + num(s.output_interval_s) + ")"};
  if (s.output_interval_s > s.duration_s)
    return ScenarioProblem{"simulation.output_interval_s",
                           "(" + num(s.output_interval_s) +
                               " s) is longer than the run (duration_s = " + num(s.duration_s) +
                               " s)"};
  if (s.duration_s / s.output_interval_s > 1e6)
    return ScenarioProblem{"simulation.output_interval_s",
                           "(" + num(s.output_interval_s) +
                               " s) with duration_s = " + num(s.duration_s) +
                               " s gives more than 10^6 output rows; use a longer interval"};
  if (auto problem = cells_per_phase_problem(s.cells_per_phase))
    return ScenarioProblem{"simulation.cells_per_phase", *problem};
  if (!(s.time_tolerance > 0 && s.time_tolerance <= 1e-2))
    return ScenarioProblem{"simulation.time_tolerance",
                           "must be in (0, 0.01] (got " + num(s.time_tolerance) + ")"};
  return std::nullopt;
}

/// [shell]: radii, length and lateral size.
std::optional<ScenarioProblem> shell_problem(const Scenario& s) {
  if (!(s.inner_radius_m >= 0))
    return ScenarioProblem{"shell.inner_radius_m",
                           "must not be negative (got " + num(s.inner_radius_m) + ")"};
  if (!(s.outer_radius_m > 0))
    return ScenarioProblem{"shell.outer_radius_m",
                           "must be positive (got " + num(s.outer_radius_m) + ")"};
  if (s.inner_radius_m > s.outer_radius_m)
    return ScenarioProblem{"shell.inner_radius_m", "(" + num(s.inner_radius_m) +
                                                       " m) is larger than outer_radius_m (" +
                                                       num(s.outer_radius_m) + " m)"};
  if (!(s.length_m > 0))
    return ScenarioProblem{"shell.length_m", "must be positive (got " + num(s.length_m) + ")"};
  if (!(s.lateral_size_m > 0))
    return ScenarioProblem{"shell.lateral_size_m",
                           "must be positive (got " + num(s.lateral_size_m) + ")"};
  return std::nullopt;
}

/// Initial and boundary temperatures against the melting point, and the boundary kinds.
std::optional<ScenarioProblem> temperature_problem(const Scenario& s) {
  const double tm = s.materials.melting_point_c;
  if (s.inner_radius_m > 0 && s.water_initial_temperature_c < tm)
    return ScenarioProblem{"water.initial_temperature_c",
                           "(" + num(s.water_initial_temperature_c) +
                               " C) is below the melting point: supercooled water is not modelled"};
  if (s.outer_radius_m > s.inner_radius_m && s.ice_initial_temperature_c > tm)
    return ScenarioProblem{"ice.initial_temperature_c", "(" + num(s.ice_initial_temperature_c) +
                                                            " C) is above the melting point"};
  if (s.geometry != Geometry::planar && s.inner_kind != InnerBoundary::symmetry)
    return ScenarioProblem{"inner_boundary.kind",
                           "a held inner temperature needs geometry = \"planar\""};
  if (s.inner_kind == InnerBoundary::temperature && s.inner_temperature_c < tm)
    return ScenarioProblem{
        "inner_boundary.temperature_c",
        "(" + num(s.inner_temperature_c) +
            " C) is below the melting point: water would freeze onto the wall (not modelled)"};
  // A body all water ([shape] fill = "water") does not drain: its faces may be held warm.
  if (s.outer_kind == OuterBoundary::temperature && s.outer_temperature_c > tm &&
      !s.shape.fill_water)
    return ScenarioProblem{
        "outer_boundary.temperature_c",
        "(" + num(s.outer_temperature_c) +
            " C) is above the melting point: a held temperature above melting on a "
            "draining surface is ill-posed (use kind = \"convective\" or \"flux\")"};
  if (s.outer_kind == OuterBoundary::convective && !(s.heat_transfer_coefficient_w_m2k > 0))
    return ScenarioProblem{"outer_boundary.heat_transfer_coefficient_w_m2k",
                           "must be positive (got " + num(s.heat_transfer_coefficient_w_m2k) + ")"};
  return std::nullopt;
}

/// No ice at t = 0 (inner radius = outer radius): it must start freezing at once.
std::optional<ScenarioProblem> empty_shell_problem(const Scenario& s) {
  const double tm = s.materials.melting_point_c;
  if (s.inner_radius_m != s.outer_radius_m) return std::nullopt;
  const bool water_at_melting = s.water_initial_temperature_c == tm;
  const bool freezes =
      (s.outer_kind == OuterBoundary::temperature && s.outer_temperature_c < tm) ||
      (s.outer_kind == OuterBoundary::convective && s.outer_temperature_c < tm &&
       water_at_melting) ||
      (s.outer_kind == OuterBoundary::flux && s.flux_w_m2 < 0 && water_at_melting) ||
      (s.outer_kind == OuterBoundary::air && water_at_melting &&
       air_heat_flux(scenario_air(s), radial_air_body(s, s.outer_radius_m), tm).total_w_m2() < 0);
  if (!freezes)
    return ScenarioProblem{
        "shell.outer_radius_m",
        "equals inner_radius_m (no ice at t = 0), so the outer boundary must freeze "
        "the water at once: "
        "a held temperature below melting, or convective/flux/air cooling of water at the "
        "melting point"};
  return std::nullopt;
}

/// kind = "air": every input inside the ranges of the correlations the body uses, over the
/// surface temperatures the run can see (the initial ice, or water, up to the melting point).
std::optional<ScenarioProblem> air_problem(const Scenario& s) {
  if (s.outer_kind != OuterBoundary::air) return std::nullopt;
  const double tm = s.materials.melting_point_c;
  const double start = s.outer_radius_m > s.inner_radius_m ? s.ice_initial_temperature_c
                                                           : s.water_initial_temperature_c;
  const double coldest = std::min({start, tm, s.outer_temperature_c});
  // An OBJ body's size is known only once meshed: its size-free ranges are checked (still air
  // on a millimetre sphere passes every size-dependent one).
  const std::optional<AirBodySize> body = scenario_air_body(s);
  Air air = scenario_air(s);
  if (!body && air.speed_m_s > 0) air.speed_m_s = 0;
  if (auto p =
          find_air_problem(air, body.value_or(AirBodySize{AirBody::sphere, 1e-3}), coldest, tm))
    return ScenarioProblem{air_input_key(p->input), p->message};
  return std::nullopt;
}

}  // namespace

std::optional<std::string> cells_per_phase_problem(std::int64_t cells) {
  if (cells < 4 || cells > 100000)
    return "must be between 4 and 100000 (got " + std::to_string(cells) + ")";
  return std::nullopt;
}

std::optional<ScenarioProblem> find_scenario_problem(const Scenario& s) {
  for (auto rule : {number_problem, simulation_problem, shell_problem, temperature_problem,
                    outside_range, air_problem, empty_shell_problem})
    if (auto p = rule(s)) return p;
  // Grid runs ([shape]); the [shell] rules above pass on its unused defaults.
  if (auto p = find_grid_problem(s)) return ScenarioProblem{p->key, p->message};
  // Each face's own [outer_boundary] table by the same rules, named by its key.
  if (!s.outer_faces.empty() && s.grid == GridGeometry::none)
    return ScenarioProblem{"outer_boundary.faces",
                           "only for geometry = \"axisymmetric\" or \"3d\" (a 1D shell has one "
                           "outer surface)"};
  const std::vector<std::string> names = body_face_names(s.shape.outer.kind);
  for (const FaceBoundary& f : s.outer_faces) {
    const std::string key = "outer_boundary.faces." + f.face;
    if (std::find(names.begin(), names.end(), f.face) == names.end())
      return ScenarioProblem{key, std::string("a ") + to_string(s.shape.outer.kind) +
                                      " body has no face '" + f.face + "'"};
    if (auto p = find_scenario_problem(with_outer_boundary(s, f.spec))) {
      const std::string outer = "outer_boundary.";
      if (p->key.rfind(outer, 0) == 0) p->key = key + "." + p->key.substr(outer.size());
      return p;
    }
  }
  return std::nullopt;
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
  if (auto p = find_scenario_problem(scenario))
    throw UserError(source_name.empty() ? scenario.source_name : source_name,
                    "key '" + p->key + "'", p->message);
}

}  // namespace thaw::sim
