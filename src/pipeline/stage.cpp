#include "src/pipeline/stage.h"

#include <algorithm>
#include <cstdio>
#include <deque>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/outcome.h"
#include "src/pipeline/rank_agreement.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;

namespace {

/// The stage's place in pipeline_stages(), from 1.
std::size_t stage_number(const Stage& stage) {
  const std::vector<Stage>& stages = pipeline_stages();
  for (std::size_t i = 0; i < stages.size(); ++i)
    if (stages[i].name == stage.name) return i + 1;
  return 0;
}

/// The stage's timing in the report, appended when it ends (also by an exception).
class StageClock {
 public:
  StageClock(RunReport& report, std::string name) : m_report(report) {
    m_timing.stage = std::move(name);
  }
  ~StageClock() {
    m_timing.seconds = StageCall{"", start}.elapsed_s();
    m_report.stages.push_back(m_timing);
  }
  StageTiming& timing() { return m_timing; }
  const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();

 private:
  RunReport& m_report;
  StageTiming m_timing;
};

/// Work this process leaves to others: a stage before --stage must already be up to date.
void require_up_to_date(PipelineRun& r, const Stage& stage) {
  if (r.manifest.is_complete(stage.name, fingerprint_of(r, stage))) return;
  throw UserError(r.o.out_dir.string(), "--stage " + r.o.stage,
                  "the " + stage.name + " stage is not up to date; run `thaw run ... --stage " +
                      stage.name + "` (or thaw run without --stage) first");
}

/// The stage's wall seconds to 0.1 ms beside its items. A note only: failing to write it does not
/// fail the stage.
void write_stage_seconds(const PipelineRun& r, const Stage& stage, double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f\n", seconds);
  const fs::path note = r.out / "run_items" / stage.name / "stage_s";
  std::error_code ec;
  fs::create_directories(note.parent_path(), ec);
  const Outcome noted = Outcome::of([&] { write_file_atomic(note, text); });
  if (noted.kind() != Outcome::Kind::user) noted.rethrow();  // a write failure only is ignored
}

}  // namespace

std::string stage_title(const Stage& stage) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "[%zu/%zu] %s", stage_number(stage), pipeline_stages().size(),
                stage.name.c_str());
  return buf;
}

const Stage& stage_named(const std::string& name) {
  const std::vector<Stage>& stages = pipeline_stages();
  const auto it =
      std::find_if(stages.begin(), stages.end(), [&](const Stage& s) { return s.name == name; });
  if (it == stages.end()) throw std::logic_error("no stage named \"" + name + "\"");
  return *it;
}

const std::string& fingerprint_of(PipelineRun& r, const Stage& stage) {
  const auto known = r.fingerprints.find(stage.name);
  if (known != r.fingerprints.end()) return known->second;
  ContentHash hash;
  hash.add(stage.tag);
  if (!stage.reads.empty()) hash.add(fingerprint_of(r, stage_named(stage.reads)));
  if (stage.fingerprint) stage.fingerprint(r, hash);
  return r.fingerprints[stage.name] = hash.hex();
}

void check_stage_inputs(PipelineRun& r) {
  if (r.o.stage.empty()) return;
  if (r.o.force)
    throw UserError("", "--force", "redoes every stage: it cannot be combined with --stage");
  std::deque<const Stage*> reads;  // in pipeline order, so the first stale one is named
  for (const Stage* s = &stage_named(r.o.stage); !s->reads.empty();) {
    s = &stage_named(s->reads);
    reads.push_front(s);
  }
  for (const Stage* s : reads) require_up_to_date(r, *s);
}

void run_stage(PipelineRun& r, const Stage& stage) {
  if (!r.wanted(stage.name)) return;
  StageClock clock(r.report, stage.name);
  const StageCall call{stage_title(stage), clock.start};
  const std::string& hash = fingerprint_of(r, stage);
  bool up_to_date = false;
  on_leader(r.ranks, [&] {
    up_to_date = r.manifest.begin_stage(stage.name, hash) && stage.outputs_exist(r);
  });
  if (r.ranks.broadcast(up_to_date ? "up to date" : "") == "up to date") {
    clock.timing().skipped = true;
    say(r.o, call.title + ": up to date");
    return;
  }
  StageDone done;
  const auto work = [&] {
    done = stage.run(r, call);
    if (r.leader && done.complete) r.manifest.mark_stage_complete(stage.name);
  };
  switch (stage.runs_on) {
    case StageRunsOn::leader:
      on_leader(r.ranks, work);
      break;
    case StageRunsOn::every_rank:
      on_every_rank(r.ranks, work);
      break;
    case StageRunsOn::farm:
      work();
      break;
  }
  clock.timing().items_done = done.items;
  clock.timing().skipped = done.skipped;
  if (r.leader) write_stage_seconds(r, stage, call.elapsed_s());
}

}  // namespace thaw::pipeline
