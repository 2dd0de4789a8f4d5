#pragma once
// `thaw run`: scenario -> simulate -> mesh -> render -> film -> inspect, each stage reading the
// previous stage's files (the only place where sim, mesh, render and inspect meet). Resumable:
// DIR/run_manifest.json fingerprints each stage's inputs, DIR/run_items/ records finished frames;
// a rerun skips what is up to date and redoes only what changed (editing the camera re-renders
// but neither re-simulates nor re-meshes). Every file is written under a temporary name and
// renamed. --frames / --stage run a part (Slurm arrays, GNU parallel), RunRanks shares the frames
// of one run among MPI ranks; the frames are byte-identical however the work is split
// (docs/pipeline.md).
//
// DIR/scenario.toml        the scenario as given (or the built-in default)
// DIR/sim/                 interfaces.csv, profiles/, summary.json (one row per film frame)
// DIR/sim/mesh/            step_NNNNNN_inner.obj / _outer.obj, manifest.json
// DIR/sim/mesh.partial/    kept meshes (and steps/: --frames parts' surfaces) until sim/mesh
// DIR/frames/frame_NNNNNN.png
// DIR/melt.mp4 (+ melt.gif), DIR/plot.png, DIR/meshes.pvd (+ meshes_vtp/, world space, normals)
// DIR/handoff/blender_scene.py, camera.json, surfaces.json, environment.hdr, meshes/ (puddles),
//   paraview_state.py, paraview_camera.pvcc: the run for Blender and other tools, referring to
//   the mesh stage's OBJs (one copy of each mesh; handoff_blender.h, docs/handoff.md)
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "src/pipeline/frame_selection.h"
#include "src/pipeline/run_ranks.h"
#include "src/pipeline/run_scenario.h"

namespace thaw::pipeline {

struct RunOptions {
  std::filesystem::path out_dir = "thaw-out";
  /// redo every stage
  bool force = false;
  /// worker threads for meshing and rendering; 0 = all cores
  int jobs = 0;
  /// no progress display
  bool quiet = false;
  /// the scenario file's text, copied to DIR/scenario.toml ("" = built-in default)
  std::string scenario_text;
  /// --frames: render only these frames (the simulation is the whole run's; unless the mesh
  /// stage is up to date, only these frames' steps are meshed, into sim/mesh.partial/steps/, and
  /// a later whole run completes the stage); the film runs only once every frame is rendered,
  /// inspect only after a whole mesh stage. Such a process leaves other processes' temporary
  /// files alone (they may be rendering into the same folder).
  std::optional<FrameSelection> frames;
  /// --preview-dir: run as a preview in this folder, starting from out_dir's simulation and
  /// meshes and keeping its finals (preview_folder.h); unset: DIR/preview when --size / --spp
  /// differ from the finals' settings
  std::optional<std::filesystem::path> preview_dir;
  /// --stage: run only this stage (one of kStageNames); the stages before it must be up to date.
  std::string stage;
  /// the processes sharing this run (MPI ranks); nullptr = this process alone
  RunRanks* ranks = nullptr;
};

/// The stages in order: simulate, mesh, render, film, inspect.
extern const std::vector<std::string> kStageNames;
/// Throws thaw::UserError("--stage", ...) unless `name` is one of kStageNames.
void check_stage_name(const std::string& name);

struct StageTiming {
  std::string stage;
  double seconds = 0;
  bool skipped = false;  ///< up to date: nothing was done
  int items_done = 0;    ///< items produced in this run (frames rendered, ...)
};

struct RunReport {
  std::filesystem::path film, gif, plot, pvd;  ///< empty if not made in this run
  /// a preview: the folder it went to (the finals in RunOptions::out_dir were kept), else empty
  std::filesystem::path preview_dir;
  /// DIR/handoff/blender_scene.py: the run in Blender in one step (handoff_blender.h)
  std::filesystem::path handoff_scene;
  /// grid runs: the solver's fields as .vti series (src/inspect/field_export.h)
  std::filesystem::path fields_pvd;
  /// 3D runs in a build with OpenVDB: DIR/handoff/vdb (handoff_vdb.h).
  std::filesystem::path handoff_vdb;
  /// the simulation's events, one line each as `thaw simulate` prints them
  /// ("event melt_onset at t = 20.6778 s, r = 0.03 m")
  std::vector<std::string> events;
  std::vector<StageTiming> stages;
  int frames = 0;
  double total_seconds = 0;
};

/// Runs every stage that is not up to date, in RunOptions::out_dir or, for a preview, in its
/// preview folder (preview_folder.h). Throws thaw::UserError (one line) on bad input or a
/// failed stage; work already finished stays on disk and in the manifest.
RunReport run_pipeline(const RunScenario& scenario, const RunOptions& options);

}  // namespace thaw::pipeline
