#pragma once
// What the stages of one `thaw run` share (stage.h): the scenario and options (quiet on all but
// the leader, which alone speaks and keeps the manifest), the ranks, the folders, the stages'
// fingerprints, the manifest, the report, and what each stage read from the one before (the
// interface history, the meshes, whether every frame is rendered). Knows no stage by name.
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sim/scenario/interface_record.h"
#include "src/mesh/mesh_series.h"
#include "src/pipeline/caption_font.h"
#include "src/pipeline/pipeline.h"
#include "src/pipeline/run_manifest.h"

namespace thaw::pipeline {

struct PipelineRun {
  PipelineRun(const RunScenario& scenario, const RunOptions& opt, RunRanks& run_ranks)
      : sc(scenario),
        o(opt),
        ranks(run_ranks),
        leader(run_ranks.leader()),
        subset(opt.frames.has_value()),
        out(opt.out_dir),
        simdir(out / "sim"),
        frames_dir(out / "frames"),
        mesh_dir(simdir / "mesh"),
        times(frame_times(scenario)),
        manifest(out / "run_manifest.json") {
    o.quiet = opt.quiet || !leader;
  }
  /// --stage: whether this process runs `stage` (every stage without --stage).
  bool wanted(const std::string& stage) const { return o.stage.empty() || o.stage == stage; }

  const RunScenario& sc;
  RunOptions o;
  RunRanks& ranks;
  const bool leader;
  /// --frames: stages after render need every frame, so this process leaves them.
  const bool subset;
  const std::filesystem::path out, simdir, frames_dir;
  /// The surfaces the render stage reads: SIMDIR/mesh, or for a --frames process whose steps
  /// alone were meshed, mesh::partial_steps_dir.
  std::filesystem::path mesh_dir;
  /// the film's frame times (simulated seconds)
  const std::vector<double> times;
  /// Each stage's fingerprint by name, made once by fingerprint_of (stage.h).
  std::map<std::string, std::string> fingerprints;
  /// The caption's font (render's fingerprint loads it); null: the built-in bitmap font.
  std::unique_ptr<CaptionFont> font;
  RunManifest manifest;
  RunReport report;

  // What the stages read from the ones before (their `read` steps, stage.h).
  /// the simulation's interface history, one row per frame time reached
  std::vector<sim::InterfaceRecord> rows;
  /// Set when this process meshed only its frames' steps (mesh_simulation_steps).
  std::optional<mesh::MeshManifest> partial_meshes;
  /// every step's surfaces (or this process's steps', when partial_meshes is set)
  mesh::MeshManifest meshes;
  /// the frames the simulation reached (one per meshed step)
  long frame_count = 0;
  /// every frame of the run rendered (not only this process's): the film can be made
  bool all_frames_done = true;
};

/// One line on stderr unless quiet.
void say(const RunOptions& o, const std::string& line);

/// "frame_000012": frame k's file name without extension (and its render item's name).
std::string frame_name(long k);

/// The frames this process is asked for: --frames or all of them, less those past the
/// simulation's end (it may end early, with no ice left); whether some were past it.
std::vector<long> frame_indexes(const PipelineRun& r, long frame_count, bool* cut = nullptr);

}  // namespace thaw::pipeline
