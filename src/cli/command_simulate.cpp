// `thaw simulate [SCENARIO.toml] --out DIR`: runs the radial Stefan solver (sim/) on a scenario
// file, or on the built-in default, and writes DIR/interfaces.csv, DIR/profiles/ and
// DIR/summary.json all at once (staged in a temporary folder, renamed into place). Parsing only.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/interrupt.h"
#include "base/progress.h"
#include "sim/format/scenario_file.h"
#include "sim/format/simulation_output.h"
#include "sim/simulate.h"
#include "src/cli/commands.h"

namespace thaw::cli {
namespace {

struct SimulateArgs {
  std::string scenario, out;
  bool quiet = false, print_default = false;
};

void run_simulate(const SimulateArgs& a) {
  if (a.print_default) {
    std::fputs(sim::default_scenario_text().c_str(), stdout);
    return;
  }
  if (a.out.empty()) throw UserError("", "--out", "required: the result folder");
  // Parse and validate before touching DIR. A scenario file may also hold thaw run's [film],
  // [mesh] and [render] sections: they are thaw run's to check, thaw simulate skips them unread
  // (docs/simulate.md), so a mistake there never stops a simulation.
  const sim::Scenario scenario =
      a.scenario.empty() ? sim::default_scenario() : sim::read_scenario_file(a.scenario);
  const std::filesystem::path out(a.out);
  if (std::filesystem::exists(out) && !std::filesystem::is_directory(out))
    throw UserError(a.out, "--out", "exists and is not a directory");
  if (const auto foreign = sim::foreign_entry(out))
    throw UserError(a.out, "--out",
                    "holds '" + *foreign +
                        "', which thaw did not write; the result folder is replaced as a whole, "
                        "so give a new or empty folder (or a previous result folder)");
  StagingDirectory staging(out);
  sim::SimulationResult result;
  {
    ProgressReporter progress(
        "simulate", static_cast<std::int64_t>(sim::output_times(scenario).size()), a.quiet);
    // A grid run's fields go to the staging folder as they are reached (none kept in memory).
    const auto times = sim::output_times(scenario);
    try {
      result = sim::simulate(scenario, times, interruptible(progress.callback()),
                             sim::field_stream(staging.path(), scenario, times.size()));
    } catch (const UserError& e) {
      // The solver's own refusals name a key of the scenario: name its file too.
      if (e.file().empty() && !a.scenario.empty() && !e.where().empty())
        throw UserError(a.scenario, e.where(), e.problem());
      throw;
    }
    progress.finish();
  }
  sim::write_simulation_outputs(staging.path(), result);
  staging.commit();
  if (a.quiet) return;
  std::printf("thaw simulate: %s -> %s\n",
              a.scenario.empty() ? "built-in default scenario" : a.scenario.c_str(),
              (out / "").string().c_str());
  const auto& last = result.snapshots.back();
  const bool grid = scenario.grid != sim::GridGeometry::none;
  if (grid)
    std::printf(
        "  %zu rows to t = %.6g s; liquid %.6g m^3, ice %.6g m^3 (volume-equivalent radii %.6g / "
        "%.6g m)\n",
        result.snapshots.size(), last.time_s, last.liquid_volume_m3, last.ice_volume_m3,
        last.inner_radius_m, last.outer_radius_m);
  else
    std::printf("  %zu rows to t = %.6g s; water|ice front %.6g m, ice surface %.6g m\n",
                result.snapshots.size(), last.time_s, last.inner_radius_m, last.outer_radius_m);
  if (grid)
    for (const auto& e : result.grid_events)
      std::printf("  event %s at t = %.6g s, at (%.4g, %.4g, %.4g) m\n", e.kind.c_str(), e.time_s,
                  e.position_m[0], e.position_m[1], e.position_m[2]);
  else
    for (const auto& e : result.events)
      std::printf("  event %s at t = %.6g s, r = %.6g m\n", e.kind.c_str(), e.time_s, e.radius_m);
  const auto& s = result.statistics;
  std::printf("  %ld steps (%ld rejected), max energy balance error %.2e, wall time %.3f s\n",
              s.steps, s.rejected_steps, s.max_step_energy_error, result.wall_time_s);
  std::printf("  results: %s, %s, %s\n", (out / "interfaces.csv").string().c_str(),
              (out / (grid ? "fields" : "profiles")).string().c_str(),
              (out / "summary.json").string().c_str());
}

}  // namespace

void register_simulate(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* cmd = app.add_subcommand("simulate",
                                     "Simulate a hollow ice shell holding water as it melts "
                                     "(radial two-phase Stefan problem with an "
                                     "ablating surface; planar, cylinder or sphere; any shape with "
                                     "geometry = axisymmetric or 3d). "
                                     "Without SCENARIO the built-in default runs (see "
                                     "--print-default and docs/simulate.md). Writes "
                                     "DIR/interfaces.csv, DIR/profiles/step_NNNNNN.csv (1D) or "
                                     "DIR/fields/step_NNNNNN.grid (grid runs) "
                                     "and DIR/summary.json.");
  cmd->add_option("scenario", args->scenario,
                  "scenario file (TOML); omit for the built-in default");
  cmd->add_option("-o,--out", args->out,
                  "result folder (replaced as a whole when the run succeeds)");
  cmd->add_flag("--print-default", args->print_default,
                "print the built-in default scenario and exit");
  cmd->add_flag("-q,--quiet", args->quiet, "no progress bar and no summary");
  cmd->callback([args] { run_simulate(*args); });
}

}  // namespace thaw::cli
