// The mesh stage: the inner and outer surface of every frame's step. Every rank meshes (distinct
// surfaces, then the steps' files, handed out like frames); the leader checks, writes the
// manifest and commits. A --frames process that leaves frames to others meshes only its frames'
// steps (kept for the whole run, which completes the stage: mesh_series.h).
#include <cstdio>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/outcome.h"
#include "src/pipeline/stages.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;

namespace {

/// What this rank's farm phases of the stage (from the first of `costs`) cost: beside the
/// stage's items, one file per rank, forgotten with them when the stage's inputs change (read by
/// bench/pipeline/mpi_scaling.sh). A note only: failing to write it does not fail the stage.
void write_cost_note(const PipelineRun& r, std::size_t first) {
  char name[32];
  std::snprintf(name, sizeof name, "costs_rank_%03d", r.ranks.rank());
  const fs::path costs = r.out / "run_items" / "mesh" / name;
  const std::vector<FarmCost>& all = r.ranks.costs();
  const std::vector<FarmCost> stage(all.begin() + static_cast<std::ptrdiff_t>(first), all.end());
  std::error_code ec;
  fs::create_directories(costs.parent_path(), ec);
  const Outcome noted = Outcome::of([&] { write_file_atomic(costs, cost_note(stage) + "\n"); });
  if (noted.kind() != Outcome::Kind::user) noted.rethrow();  // a write failure only is ignored
}

StageDone mesh(PipelineRun& r, const StageCall& call) {
  mesh::MeshOptions options = r.sc.mesh;
  options.jobs = r.o.jobs;
  const long steps = static_cast<long>(r.rows.size());
  const std::vector<long> frames = frame_indexes(r, steps);
  const bool part = r.subset && r.o.stage.empty() && static_cast<long>(frames.size()) < steps;
  ProgressReporter progress(call.title, 2 * steps, r.o.quiet);
  const std::size_t first_cost = r.ranks.costs().size();
  const mesh::MeshManifest meshes =
      part ? mesh::mesh_simulation_steps(r.simdir, options, frames, progress.callback(), r.ranks)
           : mesh::mesh_simulation_folder(r.simdir, options, progress.callback(), r.ranks);
  if (meshes.partial) r.partial_meshes = meshes;
  write_cost_note(r, first_cost);
  if (!r.leader) return {};
  if (meshes.partial) {
    progress.finish_early("for the " + std::to_string(frames.size()) +
                          " selected frames' steps only (a whole run meshes all " +
                          std::to_string(steps) + ")");
    return {static_cast<int>(frames.size()), false};
  }
  progress.finish();
  return {static_cast<int>(meshes.steps.size())};
}

}  // namespace

Stage mesh_stage() {
  Stage s;
  s.name = s.tag = "mesh";
  s.runs_on = StageRunsOn::every_rank;
  s.reads = "simulate";
  s.fingerprint = [](PipelineRun& r, ContentHash& hash) { hash.add(r.sc.mesh_text); };
  s.outputs_exist = [](const PipelineRun& r) { return fs::exists(r.mesh_dir / "manifest.json"); };
  s.run = mesh;
  s.read = [](PipelineRun& r) {
    if (r.partial_meshes) r.mesh_dir = mesh::partial_steps_dir(r.simdir);
    r.meshes = r.partial_meshes ? *r.partial_meshes
                                : mesh::read_mesh_manifest(r.mesh_dir / "manifest.json");
    r.frame_count = static_cast<long>(r.meshes.steps.size());
    r.report.frames = static_cast<int>(r.frame_count);
  };
  return s;
}

}  // namespace thaw::pipeline
