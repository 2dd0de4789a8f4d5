#include "sim/format/scenario_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <vector>

#include "base/error.h"
#include "base/format/key_table_toml.h"
#include "base/format/toml_table.h"
#include "embedded/kDefaultScenarioToml.h"
#include "embedded/kIceWaterMaterialsToml.h"
#include "sim/grid/body_faces.h"
#include "sim/grid/grid_rules.h"
#include "sim/scenario/materials_keys.h"

namespace thaw::sim {

namespace {

/// Throws the problem through the TOML table (with the key's line) when the key is in the file.
[[noreturn]] void fail_in_table(const TomlTable& root, const ScenarioProblem& p) {
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

/// The keys of an [outer_boundary] table ("faces" only in the body's own).
const std::vector<std::string> kOuterBoundaryKeys = {"kind",
                                                     "temperature_c",
                                                     "heat_transfer_coefficient_w_m2k",
                                                     "flux_w_m2",
                                                     "relative_humidity",
                                                     "speed_m_s",
                                                     "surroundings_temperature_c",
                                                     "emissivity",
                                                     "faces"};

/// Unknown tables and keys are reported before anything else: a misspelt key would otherwise
/// surface as "required key is missing" for the key it was meant to be.
void check_schema(const TomlTable& root, const std::set<std::string>& foreign_sections) {
  static const std::vector<std::pair<std::string, std::vector<std::string>>> schema = {
      {"simulation",
       {"geometry", "duration_s", "output_interval_s", "cells_per_phase", "time_tolerance",
        "cell_size_m", "max_step_s", "flow"}},
      {"shape", {"outer", "cavity", "fill"}},
      {"shell", {"inner_radius_m", "outer_radius_m", "length_m", "lateral_size_m"}},
      {"water", {"initial_temperature_c"}},
      {"ice", {"initial_temperature_c"}},
      {"inner_boundary", {"kind", "temperature_c"}},
      {"outer_boundary", kOuterBoundaryKeys},
      {"materials", key_names(materials_keys())}};
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
  const std::string fill = t.get_string("fill", "ice");
  if (fill != "ice" && fill != "water")
    t.fail("fill", "unknown fill '" + fill + "' (expected ice or water)");
  shape.fill_water = fill == "water";
  return shape;
}

Materials parse_materials(const TomlTable& t, Materials m) {
  // The properties by their rows (their ranges are rules: scenario_rules.cpp); the flowing
  // water's keys depend on each other, read below.
  for (const MaterialsKey& row : materials_keys())
    if (!row.extra.flow) read_key(t, row, m);
  if (t.has("water_density_model")) {
    const std::string model = t.get_string("water_density_model");
    if (model == "water")
      m.water_density_model = Materials::DensityModel::water;
    else if (model == "linear")
      m.water_density_model = Materials::DensityModel::linear;
    else
      t.fail("water_density_model", "unknown model '" + model + "' (expected water or linear)");
  }
  const bool linear = m.water_density_model == Materials::DensityModel::linear;
  reject_unless(t, "water_expansion_per_k", linear,
                "only used with water_density_model = \"linear\"");
  if (linear) {
    if (!t.has("water_expansion_per_k") && !(m.water_expansion_per_k > 0))
      t.fail("water_density_model",
             "a linear fluid needs water_expansion_per_k (its expansion coefficient, 1/K)");
    m.water_expansion_per_k = t.require_positive(
        "water_expansion_per_k", t.get_double("water_expansion_per_k", m.water_expansion_per_k));
  }
  if (t.has("water_viscosity_pa_s"))
    m.water_viscosity_pa_s =
        t.require_positive("water_viscosity_pa_s", t.get_double("water_viscosity_pa_s"));
  return m;
}

bool uses_outer_temperature(OuterBoundary kind) {
  return kind == OuterBoundary::temperature || kind == OuterBoundary::convective ||
         kind == OuterBoundary::air;
}

/// [simulation]: the geometry, the times and the keys of the solver the geometry selects.
void parse_simulation(const TomlTable& sim, Scenario& s) {
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
  reject_unless(sim, "flow", grid,
                "the 1D geometries conduct only; flow needs geometry = \"axisymmetric\" or \"3d\"");
  const std::int64_t cells = sim.get_int("cells_per_phase", s.cells_per_phase);
  if (auto problem = cells_per_phase_problem(cells)) sim.fail("cells_per_phase", *problem);
  s.cells_per_phase = static_cast<int>(cells);
  s.time_tolerance = sim.get_double("time_tolerance", s.time_tolerance);
  if (grid) {
    if (sim.has("cell_size_m"))
      s.cell_size_m = sim.require_positive("cell_size_m", sim.get_double("cell_size_m"));
    s.max_step_s = sim.require_positive("max_step_s", sim.get_double("max_step_s", s.max_step_s));
    if (sim.has("flow")) {  // the default (water flows wherever there is water): parse_scenario
      const std::string flow = sim.get_string("flow");
      if (flow != "none" && flow != "natural_convection")
        sim.fail("flow", "unknown flow '" + flow + "' (expected natural_convection or none)");
      s.natural_convection = flow == "natural_convection";
    }
  }
}

/// [shape] for grid runs, [shell] for the 1D geometries; the other table is an error.
void parse_body(const TomlTable& root, Scenario& s) {
  if (s.grid != GridGeometry::none) {
    if (root.has("shell"))
      root.fail("shell", "[shell] describes the 1D geometries; geometry = \"" +
                             root.table("simulation").get_string("geometry") + "\" takes [shape]");
    s.shape = parse_shape(root.table("shape"));
    return;
  }
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

/// [inner_boundary] (planar runs only): symmetry or a held temperature.
void parse_inner_boundary(const TomlTable& root, Scenario& s) {
  const auto inner = root.optional_table("inner_boundary");
  if (!inner) return;
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
    inner->fail("kind", "unknown inner boundary '" + kind + "' (expected symmetry or temperature)");
  }
  reject_unless(*inner, "temperature_c", s.inner_kind == InnerBoundary::temperature,
                "only used with kind = \"temperature\"");
}

/// [outer_boundary]: its kind and exactly the keys that kind uses.
void parse_outer_boundary(const TomlTable& outer, Scenario& s) {
  const std::string kind = outer.get_string("kind");
  if (kind == "temperature")
    s.outer_kind = OuterBoundary::temperature;
  else if (kind == "convective")
    s.outer_kind = OuterBoundary::convective;
  else if (kind == "flux")
    s.outer_kind = OuterBoundary::flux;
  else if (kind == "insulated")
    s.outer_kind = OuterBoundary::insulated;
  else if (kind == "air")
    s.outer_kind = OuterBoundary::air;
  else
    outer.fail("kind", "unknown outer boundary '" + kind +
                           "' (expected temperature, convective, flux, insulated or air)");
  const bool uses_t = uses_outer_temperature(s.outer_kind);
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
  const bool air = s.outer_kind == OuterBoundary::air;
  for (const char* key :
       {"relative_humidity", "speed_m_s", "surroundings_temperature_c", "emissivity"})
    reject_unless(outer, key, air, "only used with kind = \"air\"");
  if (!air) return;
  s.relative_humidity = outer.get_double("relative_humidity");
  s.air_speed_m_s = outer.get_double("speed_m_s", 0.0);
  if (outer.has("surroundings_temperature_c"))
    s.surroundings_temperature_c = outer.get_double("surroundings_temperature_c");
  s.emissivity = outer.get_double("emissivity", s.emissivity);
}

/// [outer_boundary.faces.NAME]: a whole [outer_boundary] table for each named face the body
/// has (sim/grid/body_faces.h), in the file's order.
void parse_outer_faces(const TomlTable& outer, Scenario& s) {
  const auto faces = outer.optional_table("faces");
  if (!faces) return;
  if (s.grid == GridGeometry::none)
    outer.fail("faces",
               "only for geometry = \"axisymmetric\" or \"3d\" (a 1D shell has one "
               "outer surface)");
  const std::vector<std::string> names = body_face_names(s.shape.outer.kind);
  for (const std::string& name : faces->keys()) {
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      std::string list;
      for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
      faces->fail(name, std::string("a ") + to_string(s.shape.outer.kind) + " body has no face '" +
                            name + "' (its faces: " + list + ")");
    }
    const TomlTable face = faces->table(name);
    for (const std::string& key : face.keys())
      if (key == "faces" || std::find(kOuterBoundaryKeys.begin(), kOuterBoundaryKeys.end(), key) ==
                                kOuterBoundaryKeys.end())
        face.fail(key, "unknown key");
    Scenario own = s;  // the face's table read into the same fields, then kept apart
    parse_outer_boundary(face, own);
    s.outer_faces.push_back({name, outer_boundary_spec(own)});
  }
}

}  // namespace

Materials default_materials() {
  static const Materials m = [] {
    const TomlTable t = TomlTable::parse_string(std::string(kIceWaterMaterialsToml),
                                                "<built-in data/materials/ice_water.toml>");
    Materials out = parse_materials(t, Materials{});
    // every key of the data file is required: a renamed key must not fall back silently
    for (const MaterialsKey& row : materials_keys())
      if (!row.extra.flow && !t.has(std::string(row.name)))
        t.fail(std::string(row.name), "missing from the built-in material table");
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
  parse_simulation(root.table("simulation"), s);
  parse_body(root, s);
  if (s.grid == GridGeometry::none || s.shape.cavity || s.shape.fill_water || root.has("water"))
    s.water_initial_temperature_c = root.table("water").get_double("initial_temperature_c");
  // [simulation] flow defaults to natural convection wherever a grid run holds water (issue 24):
  // a body with a cavity, or a body all water (a solid body's [water] table holds no water).
  if (s.grid != GridGeometry::none && !root.table("simulation").has("flow"))
    s.natural_convection = s.shape.cavity.has_value() || s.shape.fill_water;
  if (!s.shape.fill_water || root.has("ice"))
    s.ice_initial_temperature_c = root.table("ice").get_double("initial_temperature_c");
  parse_inner_boundary(root, s);
  parse_outer_boundary(root.table("outer_boundary"), s);
  parse_outer_faces(root.table("outer_boundary"), s);
  if (auto mat = root.optional_table("materials")) s.materials = parse_materials(*mat, s.materials);
  // Unset boundary temperatures follow the (possibly overridden) melting point.
  if (s.inner_kind == InnerBoundary::symmetry) s.inner_temperature_c = s.materials.melting_point_c;
  if (!uses_outer_temperature(s.outer_kind)) s.outer_temperature_c = s.materials.melting_point_c;
  for (FaceBoundary& f : s.outer_faces)
    if (!uses_outer_temperature(f.spec.kind)) f.spec.temperature_c = s.materials.melting_point_c;

  // check_schema() has already rejected every unknown key outside the foreign sections.
  if (foreign_sections.empty()) root.check_no_unknown_keys();
  if (auto p = find_scenario_problem(s)) fail_in_table(root, *p);
  return s;
}

Scenario parse_scenario_string(const std::string& text, const std::string& source_name) {
  return parse_scenario(TomlTable::parse_string(text, source_name));
}

Scenario read_scenario_file(const std::filesystem::path& path) {
  return parse_scenario(TomlTable::parse_file(path));
}

nlohmann::json scenario_to_json(const Scenario& s) {
  nlohmann::json j;
  j["simulation"] = {
      {"geometry", to_string(s.geometry)},        {"duration_s", s.duration_s},
      {"output_interval_s", s.output_interval_s}, {"cells_per_phase", s.cells_per_phase},
      {"time_tolerance", s.time_tolerance},       {"flow", "none (the 1D solvers conduct only)"}};
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
    j["simulation"]["flow"] = s.natural_convection ? "natural_convection" : "none";
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
    if (s.shape.fill_water) j["shape"]["fill"] = "water";
  }
  j["water"] = {{"initial_temperature_c", s.water_initial_temperature_c}};
  j["ice"] = {{"initial_temperature_c", s.ice_initial_temperature_c}};
  j["inner_boundary"] = {{"kind", to_string(s.inner_kind)}};
  if (s.inner_kind == InnerBoundary::temperature)
    j["inner_boundary"]["temperature_c"] = s.inner_temperature_c;
  const auto outer_json = [](const OuterBoundarySpec& b) {
    nlohmann::json outer = {{"kind", to_string(b.kind)}};
    if (b.kind == OuterBoundary::temperature || b.kind == OuterBoundary::convective ||
        b.kind == OuterBoundary::air)
      outer["temperature_c"] = b.temperature_c;
    if (b.kind == OuterBoundary::air) {
      outer["relative_humidity"] = b.relative_humidity;
      outer["speed_m_s"] = b.air_speed_m_s;
      outer["surroundings_temperature_c"] = b.surroundings_temperature_c.value_or(b.temperature_c);
      outer["emissivity"] = b.emissivity;
    }
    if (b.kind == OuterBoundary::convective)
      outer["heat_transfer_coefficient_w_m2k"] = b.heat_transfer_coefficient_w_m2k;
    if (b.kind == OuterBoundary::flux) outer["flux_w_m2"] = b.flux_w_m2;
    return outer;
  };
  j["outer_boundary"] = outer_json(outer_boundary_spec(s));
  for (const FaceBoundary& f : s.outer_faces)
    j["outer_boundary"]["faces"][f.face] = outer_json(f.spec);
  const Materials& m = s.materials;
  j["materials"] = nlohmann::json::object();
  for (const MaterialsKey& row : materials_keys())
    if (!row.extra.flow)
      j["materials"][std::string(row.name)] = m.*(std::get<NumberKey<Materials>>(row.value).field);
  if (s.natural_convection) {
    const bool linear = m.water_density_model == Materials::DensityModel::linear;
    j["materials"]["water_density_model"] = linear ? "linear" : "water";
    if (linear) j["materials"]["water_expansion_per_k"] = m.water_expansion_per_k;
    if (m.water_viscosity_pa_s > 0) j["materials"]["water_viscosity_pa_s"] = m.water_viscosity_pa_s;
  }
  return j;
}

}  // namespace thaw::sim
