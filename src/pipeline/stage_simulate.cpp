// The simulate stage: the solver run once, sampled at exactly the film's frame times, by the
// leader (the other ranks wait). Every later stage reads its interface history.
#include <array>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/interrupt.h"
#include "base/progress.h"
#include "sim/format/interface_history.h"
#include "sim/format/simulation_output.h"
#include "sim/simulate.h"
#include "src/pipeline/input_files.h"
#include "src/pipeline/stages.h"
#include "thaw_version.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;

namespace {

/// The simulation's events as `thaw simulate` prints them, from DIR/sim/summary.json.
std::vector<std::string> event_lines(const fs::path& summary_json) {
  std::vector<std::string> lines;
  std::ifstream in(summary_json);
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    char buf[256];
    for (const auto& e : j.at("events")) {
      const std::string kind = e.at("kind").get<std::string>();
      const double t = e.at("time_s").get<double>();
      if (e.contains("position_m")) {
        const auto p = e.at("position_m").get<std::array<double, 3>>();
        std::snprintf(buf, sizeof buf, "event %s at t = %.6g s, at (%.4g, %.4g, %.4g) m",
                      kind.c_str(), t, p[0], p[1], p[2]);
      } else {
        std::snprintf(buf, sizeof buf, "event %s at t = %.6g s, r = %.6g m", kind.c_str(), t,
                      e.at("radius_m").get<double>());
      }
      lines.push_back(buf);
    }
  } catch (const nlohmann::json::exception& e) {
    throw UserError(summary_json.string(), "", std::string("malformed summary: ") + e.what());
  }
  return lines;
}

StageDone simulate(PipelineRun& r, const StageCall& call) {
  ProgressReporter progress(call.title, static_cast<long>(r.times.size()), r.o.quiet);
  const sim::SimulationResult result =
      sim::simulate(r.sc.simulation, r.times, interruptible(progress.callback()));
  StagingDirectory stage(r.simdir);
  sim::write_simulation_outputs(stage.path(), result);
  stage.commit();
  progress.set_done(static_cast<long>(result.snapshots.size()));
  if (result.ended_early)
    progress.finish_early("frame times: the ice is gone at t = " +
                          ProgressReporter::format_duration(result.snapshots.back().time_s));
  else
    progress.finish();
  return {static_cast<int>(result.snapshots.size())};
}

}  // namespace

Stage simulate_stage() {
  Stage s;
  s.name = s.tag = "simulate";
  s.runs_on = StageRunsOn::leader;
  s.fingerprint = [](PipelineRun& r, ContentHash& hash) {
    hash.add(THAW_VERSION_STRING).add(r.sc.simulation_text);
    for (double t : r.times) hash.add(t);
    add_input_files(hash, simulation_input_files(r.sc));  // a [shape] OBJ
  };
  s.outputs_exist = [](const PipelineRun& r) {
    return fs::exists(r.simdir / "interfaces.csv") && fs::exists(r.simdir / "summary.json");
  };
  s.run = simulate;
  s.read = [](PipelineRun& r) {
    r.report.events = event_lines(r.simdir / "summary.json");
    r.rows = sim::read_interfaces_csv(r.simdir / "interfaces.csv");
  };
  return s;
}

}  // namespace thaw::pipeline
