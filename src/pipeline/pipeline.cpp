// run_pipeline: the stages of stages.h in order, each through run_stage (stage.h), after the
// output folder is made ready. What a stage does lives in its own file.
#include "src/pipeline/pipeline.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "base/atomic_file.h"
#include "base/error.h"
#include "src/pipeline/preview_folder.h"
#include "src/pipeline/rank_agreement.h"
#include "src/pipeline/stages.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;

const std::vector<Stage>& pipeline_stages() {
  static const std::vector<Stage> stages = {simulate_stage(), mesh_stage(), render_stage(),
                                            film_stage(), inspect_stage()};
  return stages;
}

namespace {

std::vector<std::string> stage_names() {
  std::vector<std::string> names;
  for (const Stage& s : pipeline_stages()) names.push_back(s.name);
  return names;
}

/// The output folder made ready (stale temporaries removed, --force, scenario.toml) by the
/// leader, then every rank goes on together.
void prepare_output(PipelineRun& r) {
  if (r.leader) {
    ensure_directory(r.out);
    // A run killed while writing leaves its temporary file behind; the finished outputs are
    // intact. A --frames process may share the folder with live processes on other machines,
    // whose process ids mean nothing here: it leaves the cleaning to a whole run.
    if (!r.subset) remove_stale_temporaries(r.out);
    if (r.o.force) r.manifest.clear();
    if (!r.o.scenario_text.empty()) write_file_atomic(r.out / "scenario.toml", r.o.scenario_text);
  }
  r.ranks.barrier();
  if (r.o.jobs > 0) omp_set_num_threads(r.o.jobs);
}

}  // namespace

const std::vector<std::string> kStageNames = stage_names();

void check_stage_name(const std::string& name) {
  std::string names;
  for (std::size_t i = 0; i < kStageNames.size(); ++i) {
    if (kStageNames[i] == name) return;
    names += (i == 0 ? "" : i + 1 == kStageNames.size() ? " or " : ", ") + kStageNames[i];
  }
  throw UserError("", "--stage", "must be " + names + " (got \"" + name + "\")");
}

void say(const RunOptions& o, const std::string& line) {
  if (!o.quiet) std::fprintf(stderr, "%s\n", line.c_str());
}

std::string frame_name(long k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%06ld", k);
  return buf;
}

std::vector<long> frame_indexes(const PipelineRun& r, long frame_count, bool* cut) {
  std::vector<long> selected;
  if (!r.o.frames) {
    for (long k = 0; k < frame_count; ++k) selected.push_back(k);
    return selected;
  }
  selected = r.o.frames->resolve(static_cast<long>(r.times.size()));
  const auto past =
      std::find_if(selected.begin(), selected.end(), [&](long k) { return k >= frame_count; });
  if (cut) *cut = past != selected.end();
  selected.erase(past, selected.end());
  return selected;
}

RunReport run_pipeline(const RunScenario& sc, const RunOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<RunRanks> alone = opt.ranks ? nullptr : single_process();
  RunRanks& ranks = opt.ranks ? *opt.ranks : *alone;
  // A preview runs in its own folder, started from DIR's simulation and meshes: the leader
  // decides and prepares it, every rank goes there.
  RunFolder folder;
  on_leader(ranks, [&] {
    folder = choose_run_folder(sc, opt);
    if (folder.preview) start_preview_from(opt.out_dir, folder.dir);
  });
  RunOptions o = opt;
  o.out_dir = ranks.broadcast(folder.dir.string());
  if (o.out_dir != opt.out_dir && ranks.leader()) say(o, folder.why);
  PipelineRun r(sc, o, ranks);
  if (o.out_dir != opt.out_dir) r.report.preview_dir = o.out_dir;
  check_stage_inputs(r);
  prepare_output(r);
  bool past_stage = false;  // --stage: the asked stage is done; later stages are left
  for (const Stage& stage : pipeline_stages()) {
    // A stage waiting for work left to other processes (--frames) ends the run, as does --stage.
    if (const std::string why = stage.waits ? stage.waits(r) : ""; !why.empty()) {
      say(r.o, stage_title(stage) + ": " + why);
      break;
    }
    if (past_stage) break;
    run_stage(r, stage);
    if (stage.read) stage.read(r);
    past_stage = r.o.stage == stage.name;
  }
  r.report.total_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r.report;
}

}  // namespace thaw::pipeline
