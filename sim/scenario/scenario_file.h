#pragma once
// Scenario TOML <-> Scenario: parsing with every key checked (unknown keys are errors naming the
// key and its line), validation of the physics (one line naming file, key and problem), the
// built-in defaults (data/materials/ice_water.toml, data/scenarios/default.toml, embedded in the
// binary) and the echo of every effective parameter into summary.json. Knows nothing of the solver.
#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "sim/scenario/scenario.h"

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

/// Parses a scenario; throws thaw::UserError("file", "line N, key 'a.b'", problem).
Scenario parse_scenario(const TomlTable& table);
Scenario parse_scenario_string(const std::string& text, const std::string& source_name);
Scenario read_scenario_file(const std::filesystem::path& path);

/// Checks a scenario built in code (the parser applies the same rules with line numbers);
/// throws thaw::UserError(source_name, key, problem).
void validate_scenario(const Scenario& scenario, const std::string& source_name = "scenario");

/// Every effective parameter, keyed as in the scenario file (summary.json "parameters").
nlohmann::json scenario_to_json(const Scenario& scenario);

}  // namespace thaw::sim
