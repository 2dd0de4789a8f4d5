#pragma once
// The physics rules every scenario must satisfy, written once: the scenario parser (with the
// key's line, sim/format/scenario_file.h), scenarios built in code (validate_scenario, called
// by the solvers) and the naming of the likely cause when a solver fails on a valid scenario.
// Part of the sim core: knows nothing of TOML or JSON (ranges documented in docs/simulate.md).
#include <cstdint>
#include <optional>
#include <string>

#include "sim/scenario/scenario.h"

namespace thaw::sim {

/// A broken rule: the dotted key it concerns ("shell.inner_radius_m") and what is wrong.
struct ScenarioProblem {
  std::string key;
  std::string message;
};

/// The first rule `scenario` breaks, or nullopt.
std::optional<ScenarioProblem> find_scenario_problem(const Scenario& scenario);

/// simulation.cells_per_phase: between 4 and 100000, checked on the file's 64-bit value before it
/// is narrowed to int (the one place this limit is written).
std::optional<std::string> cells_per_phase_problem(std::int64_t cells);

/// Checks a scenario built in code (the parser applies the same rules with line numbers);
/// throws thaw::UserError(source_name, key, problem); "" names scenario.source_name.
void validate_scenario(const Scenario& scenario, const std::string& source_name = "");

/// The key most likely behind a solver failure on a valid scenario: the value farthest outside
/// the range typical scenarios use (sizes and coefficients in decades, temperatures per 100 K),
/// or simulation.time_tolerance when every value is typical; `hint` says what to try.
struct LikelyCause {
  std::string key;  ///< dotted key, e.g. "shell.inner_radius_m"
  std::string hint;
};
LikelyCause likely_cause_of_solver_failure(const Scenario& scenario);

}  // namespace thaw::sim
