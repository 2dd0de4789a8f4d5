#pragma once
// Scenario TOML <-> Scenario (the sim's file-format layer): parsing with every key checked
// (unknown keys are errors naming the key and its line), the physics rules of scenario_rules.h
// applied with the key's line, the built-in defaults (data/materials/ice_water.toml,
// data/scenarios/default.toml, embedded in the binary) and the echo of every effective parameter
// into summary.json. Knows nothing of the solver.
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <set>
#include <string>

#include "sim/scenario/scenario.h"
#include "sim/scenario/scenario_rules.h"

namespace thaw {
class TomlTable;
}

namespace thaw::sim {

/// Material defaults from the embedded data/materials/ice_water.toml.
Materials default_materials();
/// The built-in default scenario (embedded data/scenarios/default.toml).
Scenario default_scenario();
/// Text of the built-in default scenario (for --help / docs).
std::string default_scenario_text();

/// The top-level tables owned by later stages of `thaw run`: "film", "mesh", "render".
const std::set<std::string>& other_stage_tables();
/// Parses a scenario; throws thaw::UserError("file", "line N, key 'a.b'", problem). Every key
/// of the simulation's tables is checked; other_stage_tables() are skipped, unread, for their
/// owners to check (thaw simulate ignores them).
Scenario parse_scenario(const TomlTable& table);
/// Same for a document that also holds sections owned by other stages (`thaw run`'s [film],
/// [mesh], [render]): those top-level tables are left alone, and unknown keys are NOT checked
/// here; the owner of the document calls check_no_unknown_keys() once it has read everything.
Scenario parse_scenario(const TomlTable& table, const std::set<std::string>& foreign_sections);
Scenario parse_scenario_string(const std::string& text, const std::string& source_name);
Scenario read_scenario_file(const std::filesystem::path& path);

/// Every effective parameter, keyed as in the scenario file (summary.json "parameters").
nlohmann::json scenario_to_json(const Scenario& scenario);

}  // namespace thaw::sim
