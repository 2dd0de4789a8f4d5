#pragma once
// One stage of `thaw run` as data, and the one driver that runs any of them (run_stage): the
// skeleton every stage shares (wanted by --stage?, its clock, begin in the manifest, outputs on
// disk?, the up-to-date word from the leader to every rank, mark complete), the timing notes and
// the --stage rules. A stage's own file says only what it reads, what makes it redo and how it does
// its work; it never spells another stage's number. The stages in order: stages.h.
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "src/pipeline/content_hash.h"
#include "src/pipeline/pipeline_run.h"

namespace thaw::pipeline {

/// Who runs a stage's work.
enum class StageRunsOn {
  /// the leader alone; the other ranks wait for its word (a failure there fails them all)
  leader,
  /// every rank, each doing its share through the ranks' farm; the ranks agree how it ended
  every_rank,
  /// every rank, its items handed out by RunRanks::farm, which itself agrees how it ended
  farm,
};

/// What a stage's work reports back to the driver.
struct StageDone {
  /// items produced in this run by this process (frames rendered, ...)
  int items = 0;
  /// false: part of the stage is left to other processes (--frames): not marked complete
  bool complete = true;
  /// nothing was left to do, although the stage as a whole was not complete
  bool skipped = false;
};

/// What run_stage hands a stage's work: its title and its clock.
struct StageCall {
  /// "[3/5] render": the stage's place in the pipeline, for progress and messages
  std::string title;
  std::chrono::steady_clock::time_point start;
  double elapsed_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
};

struct Stage {
  /// its --stage name and its name in run_manifest.json and run_items/
  std::string name;
  StageRunsOn runs_on = StageRunsOn::leader;
  /// The first part of its fingerprint: its name, with a version once its outputs' form changed
  /// ("inspect/5"), so that older outputs are redone.
  std::string tag;
  /// The stage whose outputs it reads ("" for none): that stage's fingerprint is part of this
  /// one's, and `--stage NAME` needs it (and what it reads in turn) up to date.
  std::string reads;
  /// Adds what else makes it redo (its scenario sections, input files) to its fingerprint.
  std::function<void(PipelineRun&, ContentHash&)> fingerprint;
  /// Whether its outputs are all on disk (on the leader, when the manifest says complete).
  std::function<bool(const PipelineRun&)> outputs_exist;
  /// The work (when not up to date), on the ranks `runs_on` says.
  std::function<StageDone(PipelineRun&, const StageCall&)> run;
  /// Optional, before the stage on every rank: why it must wait for work left to other processes
  /// ("" if it need not); a stage that waits ends the run (the driver says why).
  std::function<std::string(const PipelineRun&)> waits;
  /// Optional, after the stage on every rank (whether it ran, was up to date or not wanted): reads
  /// from its outputs what later stages and the report take.
  std::function<void(PipelineRun&)> read;
};

/// The stage's fingerprint: its tag, the fingerprint of the stage it reads, and its own inputs.
/// Made once per run (PipelineRun::fingerprints); every fingerprint is made here.
const std::string& fingerprint_of(PipelineRun& r, const Stage& stage);

/// --stage NAME: the stages it reads must be up to date; throws thaw::UserError otherwise, and
/// for --stage with --force. Checked before anything is written, by every rank.
void check_stage_inputs(PipelineRun& r);

/// Runs `stage` if --stage wants it and it is not up to date: the skeleton every stage shares.
/// Appends its timing to the report and writes its wall seconds (to 0.1 ms, finer than the
/// summary's) to run_items/NAME/stage_s, a note read by bench/pipeline/mpi_scaling.sh.
void run_stage(PipelineRun& r, const Stage& stage);

/// "[3/5] render".
std::string stage_title(const Stage& stage);

/// The stages in order (stages.h), and the one named `name` (which must be one of them).
const std::vector<Stage>& pipeline_stages();
const Stage& stage_named(const std::string& name);

}  // namespace thaw::pipeline
