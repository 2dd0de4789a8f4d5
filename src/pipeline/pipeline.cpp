#include "src/pipeline/pipeline.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <exception>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/interrupt.h"
#include "base/progress.h"
#include "render/geometry/obj_loader.h"
#include "render/image/exr_io.h"
#include "render/image/image_io.h"
#include "render/integrator/aov_pass.h"
#include "render/integrator/whitted.h"
#include "render/scene/scene.h"
#include "sim/format/interface_history.h"
#include "sim/format/simulation_output.h"
#include "sim/simulate.h"
#include "src/inspect/field_export.h"
#include "src/inspect/pvd_writer.h"
#include "src/inspect/radius_plot.h"
#include "src/mesh/mesh_series.h"
#include "src/pipeline/caption_font.h"
#include "src/pipeline/content_hash.h"
#include "src/pipeline/film_encoder.h"
#include "src/pipeline/frame_camera.h"
#include "src/pipeline/frame_label.h"
#include "src/pipeline/frame_puddle.h"
#include "src/pipeline/frame_scene.h"
#include "src/pipeline/handoff_blender.h"
#include "src/pipeline/handoff_camera.h"
#include "src/pipeline/handoff_export.h"
#include "src/pipeline/handoff_vdb.h"
#include "src/pipeline/ranks_mesh_farm.h"
#include "src/pipeline/run_manifest.h"
#include "src/pipeline/water_budget.h"
#include "thaw_version.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;

namespace {

constexpr int kStages = 5;

class StageClock {
 public:
  StageClock(RunReport& report, std::string name) : m_report(report), m_start(now()) {
    m_timing.stage = std::move(name);
  }
  ~StageClock() {
    m_timing.seconds = std::chrono::duration<double>(now() - m_start).count();
    m_report.stages.push_back(m_timing);
  }
  StageTiming& timing() { return m_timing; }
  double elapsed_s() const { return std::chrono::duration<double>(now() - m_start).count(); }

 private:
  static std::chrono::steady_clock::time_point now() { return std::chrono::steady_clock::now(); }
  RunReport& m_report;
  std::chrono::steady_clock::time_point m_start;
  StageTiming m_timing;
};

std::string stage_title(int index, const char* name) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "[%d/%d] %s", index, kStages, name);
  return buf;
}

void say(const RunOptions& o, const std::string& line) {
  if (!o.quiet) std::fprintf(stderr, "%s\n", line.c_str());
}

std::string frame_name(long k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%06ld", k);
  return buf;
}

/// The scene of one frame (frame_scene.h) with the step's meshes read from the mesh stage.
render::SceneDescription frame_scene(const RunScenario& sc, const fs::path& mesh_dir,
                                     const sim::ShellGeometry& geometry,
                                     const mesh::StepRecord& step, const WaterBudget& water) {
  FrameShell shell;
  if (step.outer.file)
    shell.outer =
        std::make_shared<render::TriangleMesh>(render::load_obj(mesh_dir / *step.outer.file));
  if (step.inner.file)
    shell.inner =
        std::make_shared<render::TriangleMesh>(render::load_obj(mesh_dir / *step.inner.file));
  shell.outer_radius_m = step.outer_radius_m;
  return pipeline::frame_scene(sc, geometry, shell, water);
}

void stamp_frame_caption(render::Image& image, double time_s, const CaptionFont* font) {
  const int w = image.width(), h = image.height();
  std::vector<float> rgb(std::size_t(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto& p = image.at(x, y);
      float* q = &rgb[(std::size_t(y) * w + x) * 3];
      q[0] = p.r, q[1] = p.g, q[2] = p.b;
    }
  stamp_caption(rgb.data(), w, h, format_sim_time_label(time_s), font);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float* q = &rgb[(std::size_t(y) * w + x) * 3];
      image.at(x, y) = render::Rgb(q[0], q[1], q[2]);
    }
}

RunReport& finish_report(RunReport& report, std::chrono::steady_clock::time_point start) {
  report.total_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace

const std::vector<std::string> kStageNames = {"simulate", "mesh", "render", "film", "inspect"};

void check_stage_name(const std::string& name) {
  for (const auto& s : kStageNames)
    if (s == name) return;
  throw UserError("", "--stage",
                  "must be simulate, mesh, render, film or inspect (got \"" + name + "\")");
}

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

/// Work this process leaves to others: a stage before --stage must already be up to date.
void require_up_to_date(const RunManifest& manifest, const std::string& stage,
                        const std::string& hash, const RunOptions& opt) {
  if (manifest.is_complete(stage, hash)) return;
  throw UserError(opt.out_dir.string(), "--stage " + opt.stage,
                  "the " + stage + " stage is not up to date; run `thaw run ... --stage " + stage +
                      "` (or thaw run without --stage) first");
}

/// Runs `step` on the leader (rank 0) and tells every rank how it ended: a failure there (a user
/// error, or any other error when other ranks wait for the leader's word) is thrown on all ranks
/// as one UserError; with one rank, other errors propagate unchanged.
template <class Step>
void on_leader(RunRanks& ranks, Step&& step) {
  std::string error;
  if (ranks.leader()) try {
      step();
    } catch (const UserError& e) {
      error = e.what();
    } catch (const std::exception& e) {
      if (ranks.size() == 1) throw;
      error = std::string("internal error: ") + e.what();
    }
  error = ranks.broadcast(error);
  if (!error.empty()) throw UserError("", "", error);
}

/// Runs `step` on every rank (each doing its share) and makes them agree how it ended: the first
/// rank's failure is thrown on all ranks as one UserError. With one rank, errors propagate
/// unchanged.
template <class Step>
void on_every_rank(RunRanks& ranks, Step&& step) {
  if (ranks.size() == 1) return step();
  std::string error;
  try {
    step();
  } catch (const UserError& e) {
    error = e.what();
  } catch (const std::exception& e) {
    error = std::string("internal error: ") + e.what();
  }
  error = ranks.first_error(error);
  if (!error.empty()) throw UserError("", "", error);
}

/// What the stages of one run share: the scenario and options (quiet on all but the leader, which
/// alone speaks and keeps the manifest), the ranks, the folders, the stages' fingerprints, the
/// manifest and the report.
struct Run {
  Run(const RunScenario& scenario, const RunOptions& opt, RunRanks& run_ranks)
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
  bool wanted(const std::string& stage) const { return o.stage.empty() || o.stage == stage; }

  const RunScenario& sc;
  RunOptions o;
  RunRanks& ranks;
  const bool leader;
  /// --frames: stages after render need every frame, so this process leaves them.
  const bool subset;
  const fs::path out, simdir, frames_dir;
  /// The surfaces the render stage reads: SIMDIR/mesh, or for a --frames process whose steps
  /// alone were meshed, mesh::partial_steps_dir.
  fs::path mesh_dir;
  const std::vector<double> times;
  /// Set when this process meshed only its frames' steps (mesh_simulation_steps).
  std::optional<mesh::MeshManifest> partial_meshes;
  ContentHash sim_hash, mesh_hash, render_hash;
  bool exr_frames = false;
  std::unique_ptr<CaptionFont> font;
  RunManifest manifest;
  RunReport report;
};

/// Each stage's fingerprint: its scenario sections and the fingerprint of the stage before (and
/// the caption's font, loaded here: DejaVu Sans, or the bitmap font if it cannot be loaded).
void fingerprint_stages(Run& r) {
  const RunScenario& sc = r.sc;
  ContentHash& sim_hash = r.sim_hash;
  ContentHash& mesh_hash = r.mesh_hash;
  ContentHash& render_hash = r.render_hash;
  // What each stage depends on: its scenario sections and the fingerprint of the stage before.
  sim_hash.add("simulate").add(THAW_VERSION_STRING).add(sc.simulation_text);
  for (double t : r.times) sim_hash.add(t);
  mesh_hash.add("mesh").add(sim_hash.hex()).add(sc.mesh_text);
  render_hash.add("render")
      .add(mesh_hash.hex())
      .add(sc.render_text)
      .add(sc.film.caption ? "caption" : "");
  r.exr_frames = sc.film.frames_format == FilmSettings::FramesFormat::exr;
  if (r.exr_frames) render_hash.add("frames_format=exr/2");  // /2: the camera in the header
  // The caption's font: DejaVu Sans, or the bitmap font if it cannot be loaded (said once).
  if (sc.film.caption) {
    std::string problem;
    r.font = CaptionFont::load(kDefaultCaptionFont, problem);
    if (r.font)
      render_hash.add_file(kDefaultCaptionFont);
    else
      say(r.o, "caption: " + problem + "; using the built-in bitmap font");
  }
  for (const auto& obj : sc.scene.objects)
    if (!obj.mesh_file.empty())
      render_hash.add_file(obj.mesh_file.is_absolute() ? obj.mesh_file
                                                       : sc.scene.base_dir / obj.mesh_file);
}

/// --stage: the stages it reads must be up to date; checked before anything is written (by every
/// rank, so that all of them stop).
void check_stage_inputs(Run& r) {
  const RunOptions& o = r.o;
  const ContentHash& sim_hash = r.sim_hash;
  const ContentHash& mesh_hash = r.mesh_hash;
  const ContentHash& render_hash = r.render_hash;
  RunManifest& manifest = r.manifest;
  if (!o.stage.empty()) {
    if (o.force)
      throw UserError("", "--force", "redoes every stage: it cannot be combined with --stage");
    const std::pair<const char*, std::string> reads[] = {
        {"simulate", sim_hash.hex()}, {"mesh", mesh_hash.hex()}, {"render", render_hash.hex()}};
    const auto index =
        std::find(kStageNames.begin(), kStageNames.end(), o.stage) - kStageNames.begin();
    // inspect reads the meshes, not the frames
    const long count = o.stage == "inspect" ? 2 : static_cast<long>(index);
    for (long i = 0; i < count; ++i)
      require_up_to_date(manifest, reads[i].first, reads[i].second, o);
  }
}

/// The output folder made ready (stale temporaries removed, --force, scenario.toml) by the
/// leader, then every rank goes on together.
void prepare_output(Run& r) {
  const RunOptions& o = r.o;
  RunRanks& ranks = r.ranks;
  const bool leader = r.leader;
  const bool subset = r.subset;
  const fs::path& out = r.out;
  RunManifest& manifest = r.manifest;
  if (leader) {
    ensure_directory(out);
    // A run killed while writing leaves its temporary file behind; the finished outputs are
    // intact. A --frames process may share the folder with live processes on other machines,
    // whose process ids mean nothing here: it leaves the cleaning to a whole run.
    if (!subset) remove_stale_temporaries(out);
  }
  if (leader && o.force) manifest.clear();
  if (leader && !o.scenario_text.empty()) write_file_atomic(out / "scenario.toml", o.scenario_text);
  ranks.barrier();
  if (o.jobs > 0) omp_set_num_threads(o.jobs);
}

/// 1. Simulate, sampled at exactly the frame times (the leader; the others wait). Returns the
/// interface history every later stage reads.
std::vector<sim::InterfaceRecord> simulate_stage(Run& r) {
  const RunScenario& sc = r.sc;
  const RunOptions& o = r.o;
  RunRanks& ranks = r.ranks;
  const fs::path& simdir = r.simdir;
  const std::vector<double>& times = r.times;
  const ContentHash& sim_hash = r.sim_hash;
  RunManifest& manifest = r.manifest;
  RunReport& report = r.report;
  on_leader(ranks, [&] {
    if (r.wanted("simulate")) {
      StageClock clock(report, "simulate");
      const bool up_to_date = manifest.begin_stage("simulate", sim_hash.hex()) &&
                              fs::exists(simdir / "interfaces.csv") &&
                              fs::exists(simdir / "summary.json");
      if (up_to_date) {
        clock.timing().skipped = true;
        say(o, stage_title(1, "simulate") + ": up to date");
      } else {
        ProgressReporter progress(stage_title(1, "simulate"), static_cast<long>(times.size()),
                                  o.quiet);
        const sim::SimulationResult result =
            sim::simulate(sc.simulation, times, interruptible(progress.callback()));
        StagingDirectory stage(simdir);
        sim::write_simulation_outputs(stage.path(), result);
        stage.commit();
        progress.set_done(static_cast<long>(result.snapshots.size()));
        if (result.ended_early)
          progress.finish_early("frame times: the ice is gone at t = " +
                                ProgressReporter::format_duration(result.snapshots.back().time_s));
        else
          progress.finish();
        manifest.mark_stage_complete("simulate");
        clock.timing().items_done = static_cast<int>(result.snapshots.size());
      }
    }
  });
  report.events = event_lines(simdir / "summary.json");
  return sim::read_interfaces_csv(simdir / "interfaces.csv");
}

/// The frames this process is asked for: --frames or all of them, less those past the
/// simulation's end (it may end early, with no ice left); whether some were past it.
std::vector<long> frame_indexes(const Run& r, long frame_count, bool* cut = nullptr) {
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

/// frame_indexes, saying once that frames past the simulation's end do not exist.
std::vector<long> selected_frames(const Run& r, long frame_count) {
  bool cut = false;
  std::vector<long> selected = frame_indexes(r, frame_count, &cut);
  if (cut) {
    const long past = r.o.frames->resolve(static_cast<long>(r.times.size()))[selected.size()];
    say(r.o, stage_title(3, "render") + ": frames from " + std::to_string(past) +
                 " on do not exist (the simulation ended early with " +
                 std::to_string(frame_count) + " frames)");
  }
  return selected;
}

/// 2. Mesh the inner and outer surface of every frame: every rank meshes (distinct surfaces, then
/// the steps' files, handed out like frames); the leader checks, writes the manifest and commits.
void mesh_stage(Run& r, const std::vector<sim::InterfaceRecord>& rows) {
  const RunScenario& sc = r.sc;
  const RunOptions& o = r.o;
  RunRanks& ranks = r.ranks;
  const bool leader = r.leader;
  const fs::path& simdir = r.simdir;
  const fs::path& mesh_dir = r.mesh_dir;
  const ContentHash& mesh_hash = r.mesh_hash;
  RunManifest& manifest = r.manifest;
  RunReport& report = r.report;
  if (r.wanted("mesh")) {
    StageClock clock(report, "mesh");
    mesh::MeshOptions options = sc.mesh;
    options.jobs = o.jobs;
    bool up_to_date = false;
    on_leader(ranks, [&] {
      up_to_date =
          manifest.begin_stage("mesh", mesh_hash.hex()) && fs::exists(mesh_dir / "manifest.json");
    });
    up_to_date = ranks.broadcast(up_to_date ? "up to date" : "") == "up to date";
    if (up_to_date) {
      clock.timing().skipped = true;
      say(o, stage_title(2, "mesh") + ": up to date");
    } else {
      // A --frames process that leaves frames to others meshes only its frames' steps (kept
      // for the whole run, which completes the stage: mesh_series.h).
      const std::vector<long> frames = frame_indexes(r, static_cast<long>(rows.size()));
      const bool part = r.subset && o.stage.empty() && frames.size() < rows.size();
      on_every_rank(ranks, [&] {
        ProgressReporter progress(stage_title(2, "mesh"), static_cast<long>(2 * rows.size()),
                                  o.quiet);
        RanksMeshFarm farm(ranks);
        const mesh::MeshManifest meshes =
            part ? mesh::mesh_simulation_steps(simdir, options, frames, progress.callback(), farm)
                 : mesh::mesh_simulation_folder(simdir, options, progress.callback(), farm);
        if (meshes.partial) r.partial_meshes = meshes;
        // What this rank's farm phases cost (bench/pipeline/mpi_scaling.sh): beside the frames'
        // notes, one file per rank, forgotten with the stage's items when its inputs change. A
        // note only: failing to write it does not fail the stage.
        char name[32];
        std::snprintf(name, sizeof name, "costs_rank_%03d", ranks.rank());
        const fs::path costs = r.out / "run_items" / "mesh" / name;
        std::error_code ec;
        fs::create_directories(costs.parent_path(), ec);
        try {
          write_file_atomic(costs, cost_note(farm.costs()) + "\n");
        } catch (const UserError&) {
        }
        if (!leader) return;
        if (meshes.partial) {
          progress.finish_early("for the " + std::to_string(frames.size()) +
                                " selected frames' steps only (a whole run meshes all " +
                                std::to_string(rows.size()) + ")");
          clock.timing().items_done = static_cast<int>(frames.size());
          return;
        }
        progress.finish();
        manifest.mark_stage_complete("mesh");
        clock.timing().items_done = static_cast<int>(meshes.steps.size());
      });
      // The stage's wall seconds to 0.1 ms (the summary's "0.10 s" is too coarse for a stage this
      // short: bench/pipeline/mpi_scaling.sh reads this). A note, like the costs above.
      if (leader) {
        char text[32];
        std::snprintf(text, sizeof text, "%.4f\n", clock.elapsed_s());
        try {
          write_file_atomic(r.out / "run_items" / "mesh" / "stage_s", text);
        } catch (const UserError&) {
        }
      }
    }
  }
}

/// Renders frame k and writes its PNG (and EXR) atomically; nothing if interrupted.
void render_frame(const Run& r, const RunScenario& framed, const mesh::MeshManifest& meshes,
                  const std::vector<WaterBudget>& water, long k) {
  const RunScenario& sc = r.sc;
  const fs::path& frames_dir = r.frames_dir;
  throw_if_interrupted();
  const mesh::StepRecord& step = meshes.steps[static_cast<std::size_t>(k)];
  const render::Scene scene = render::build_scene(frame_scene(
      framed, r.mesh_dir, meshes.geometry, step, water.at(static_cast<std::size_t>(step.step))));
  render::RenderOptions ro;
  ro.threads = r.o.jobs;
  render::RenderResult result = render::render(scene, ro);
  throw_if_interrupted();  // the render skipped its remaining tiles: write nothing
  if (r.exr_frames) {      // for compositing: no caption, linear, with the AOV layers
    const render::AovImage aovs = render::render_aovs(scene, r.o.jobs);
    const CameraMatrices cam =
        camera_matrices(framed.scene.camera, sc.scene.image.width, sc.scene.image.height);
    render::write_exr(frames_dir / (frame_name(k) + ".exr"), result.image, &aovs,
                      {sc.source_name, step.time_s, sc.scene.image.samples_per_pixel,
                       sc.scene.image.exposure, cam.world_to_camera, cam.world_to_ndc});
  }
  if (sc.film.caption) stamp_frame_caption(result.image, step.time_s, r.font.get());
  render::write_png(frames_dir / (frame_name(k) + ".png"), result.image, sc.scene.image.exposure, 8,
                    sc.scene.image.view);
}

/// 3. Render one frame per step, handed out over the ranks. Returns whether every frame of the run
/// (not only this process's) is done, which the film needs.
bool render_stage(Run& r, const mesh::MeshManifest& meshes,
                  const std::vector<sim::InterfaceRecord>& rows) {
  const RunScenario& sc = r.sc;
  const RunOptions& o = r.o;
  RunRanks& ranks = r.ranks;
  const bool leader = r.leader;
  const bool subset = r.subset;
  const fs::path& out = r.out;
  const fs::path& frames_dir = r.frames_dir;
  const ContentHash& render_hash = r.render_hash;
  const bool exr_frames = r.exr_frames;
  RunManifest& manifest = r.manifest;
  RunReport& report = r.report;
  const long frame_count = static_cast<long>(meshes.steps.size());
  // The built-in camera frames the shell's largest extent over the run: one camera for all frames.
  RunScenario framed = sc;
  framed.scene.camera = run_camera(sc, rows, meshes.geometry);
  const std::vector<WaterBudget> water =
      water_budget(rows, meshes.geometry, sc.simulation.materials.ice_density_kg_m3,
                   sc.simulation.materials.water_density_kg_m3);
  bool all_frames_done = true;
  if (r.wanted("render")) {
    StageClock clock(report, "render");
    bool complete = false;
    if (leader) {
      ensure_directory(frames_dir);
      complete = manifest.begin_stage("render", render_hash.hex());
      // Frames beyond the current count belong to an older, longer run.
      if (!subset)
        for (long k = frame_count; fs::exists(frames_dir / (frame_name(k) + ".png")); ++k) {
          fs::remove(frames_dir / (frame_name(k) + ".png"));
          fs::remove(frames_dir / (frame_name(k) + ".exr"));
        }
    }
    ranks.barrier();
    // The leader has (re)started the stage under this fingerprint: read it back on every rank.
    if (!leader) manifest = RunManifest(out / "run_manifest.json");
    const std::vector<long> selected = selected_frames(r, frame_count);
    std::vector<long> todo;
    for (long k : selected)
      if (!(manifest.item_done("render", frame_name(k)) &&
            fs::exists(frames_dir / (frame_name(k) + ".png")) &&
            (!exr_frames || fs::exists(frames_dir / (frame_name(k) + ".exr")))))
        todo.push_back(k);
    const long done_before = static_cast<long>(selected.size() - todo.size());
    ProgressReporter progress(stage_title(3, "render"), static_cast<long>(selected.size()),
                              o.quiet || todo.empty());
    progress.set_done(done_before);
    long rendered_here = 0;
    ranks.farm(
        todo,
        [&](long k) {
          // What the frame cost, on its item's second line (bench/pipeline/mpi_scaling.sh reads
          // it for the scaling model): wall and process CPU seconds, and which rank.
          const auto start = std::chrono::steady_clock::now();
          const std::clock_t cpu_start = std::clock();
          render_frame(r, framed, meshes, water, k);
          char note[128];
          std::snprintf(
              note, sizeof note, "rank %d wall_s %.3f cpu_s %.3f", ranks.rank(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
              static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
          manifest.mark_item_done("render", frame_name(k), note);
          ++rendered_here;
          return std::string();
        },
        [&](long n, long) { progress.set_done(done_before + n); });
    progress.finish();
    clock.timing().items_done = static_cast<int>(leader ? todo.size() : rendered_here);
    clock.timing().skipped = todo.empty();
    // Every frame (not only this process's) must be there before the film is made.
    for (long k = 0; k < frame_count && all_frames_done; ++k)
      all_frames_done = manifest.item_done("render", frame_name(k));
    if (leader && all_frames_done) manifest.mark_stage_complete("render");
    if (complete && todo.empty()) say(o, stage_title(3, "render") + ": up to date");
    if (!all_frames_done) {
      long rendered = 0;
      for (long k = 0; k < frame_count; ++k)
        rendered += manifest.item_done("render", frame_name(k));
      say(o, "[4/5] film: waits for every frame (" + std::to_string(rendered) + " of " +
                 std::to_string(frame_count) +
                 " rendered); render the rest with --frames, then run thaw run again");
    }
  }
  return all_frames_done;
}

/// 4. The film (and GIF) from every frame (the leader).
void film_stage(Run& r, long frame_count) {
  const RunScenario& sc = r.sc;
  const RunOptions& o = r.o;
  const fs::path& out = r.out;
  const fs::path& frames_dir = r.frames_dir;
  const ContentHash& render_hash = r.render_hash;
  RunManifest& manifest = r.manifest;
  RunReport& report = r.report;
  ContentHash film_hash;
  film_hash.add("film")
      .add(render_hash.hex())
      .add(sc.film_text)
      .add(static_cast<double>(frame_count));
  if (r.wanted("film")) {
    report.film = out / "melt.mp4";
    if (sc.film.gif) report.gif = out / "melt.gif";
    StageClock clock(report, "film");
    const bool up_to_date = manifest.begin_stage("film", film_hash.hex()) &&
                            fs::exists(report.film) && (!sc.film.gif || fs::exists(report.gif));
    if (up_to_date) {
      clock.timing().skipped = true;
      say(o, stage_title(4, "film") + ": up to date");
    } else {
      say(o, stage_title(4, "film") + ": encoding " + std::to_string(frame_count) +
                 " frames with ffmpeg");
      FilmRequest request{frames_dir / "frame_%06d.png", 0, static_cast<int>(frame_count),
                          sc.film.film_fps(), 18};
      encode_mp4(request, report.film);
      if (sc.film.gif) encode_gif(request, report.gif);
      say(o, stage_title(4, "film") + ": " + std::to_string(frame_count) + "/" +
                 std::to_string(frame_count) + " done in " +
                 ProgressReporter::format_duration(clock.elapsed_s()));
      manifest.mark_stage_complete("film");
      clock.timing().items_done = 1;
    }
  }
}

/// 5. Inspect: the radius plot, the ParaView series, (grid runs) the OpenVDB volumes, the surfaces
/// placed where the film shows them, and the scene hand-off (handoff_blender.h). Under MPI the
/// steps are handed out like the mesh stage's items (each rank writes its steps' .vtp into the
/// leader's staged folder), the last rank draws the plot meanwhile, and the leader commits the
/// series and writes the grid runs' field exports and the hand-off.
void inspect_stage(Run& r, const mesh::MeshManifest& meshes,
                   const std::vector<sim::InterfaceRecord>& rows) {
  const RunScenario& sc = r.sc;
  const RunOptions& o = r.o;
  RunRanks& ranks = r.ranks;
  const bool leader = r.leader;
  const fs::path& out = r.out;
  const fs::path& simdir = r.simdir;
  const ContentHash& mesh_hash = r.mesh_hash;
  RunManifest& manifest = r.manifest;
  RunReport& report = r.report;
  if (!r.wanted("inspect")) return;
  report.plot = out / "plot.png";
  report.pvd = out / "meshes.pvd";
  report.handoff_scene = out / "handoff" / "blender_scene.py";
  ContentHash inspect_hash;
  // /5: .vtp/.vti arrays inline (Debian 12's ParaView cannot read appended data), fields placed.
  inspect_hash.add("inspect/5").add(mesh_hash.hex()).add(sc.shell.rest_on_floor ? "floor" : "");
  for (double v : sc.shell.center) inspect_hash.add(v);
  inspect_hash.add(sc.shell.floor_y);
  // The scene hand-off (handoff_blender.h) sees the scene and the film's rate.
  inspect_hash.add("handoff/2").add(sc.render_text).add(sc.film.film_fps());
#if THAW_OPENVDB
  // A build with OpenVDB adds the volumes to an older run's (/2: axisymmetric runs' too).
  inspect_hash.add("openvdb/2");
#endif
  StageClock clock(report, "inspect");
  bool up_to_date = false;
  on_leader(ranks, [&] {
    up_to_date = manifest.begin_stage("inspect", inspect_hash.hex()) && fs::exists(report.plot) &&
                 fs::exists(report.pvd) && fs::exists(report.handoff_scene);
  });
  if (ranks.broadcast(up_to_date ? "up to date" : "") == "up to date") {
    clock.timing().skipped = true;
    say(o, stage_title(5, "inspect") + ": up to date");
    return;
  }
  on_every_rank(ranks, [&] {
    ProgressReporter progress(stage_title(5, "inspect"), static_cast<long>(meshes.steps.size()),
                              o.quiet);
    // The hand-off refers to the mesh stage's OBJs (handoff_blender.h): the world-space copies
    // older runs kept in handoff/obj/ go.
    if (leader) fs::remove_all(out / "handoff" / "obj");
    // The plot by the last rank (alone: this process) before it joins the steps, so that under
    // MPI it overlaps the others' steps. Its failure waits until the steps are done: the other
    // ranks wait for this one's share of them.
    std::exception_ptr plot_failure;  // rethrown as it was (a UserError stays one)
    if (ranks.rank() == ranks.size() - 1) try {
        inspect::write_radius_plot(simdir, report.plot);
      } catch (...) {
        if (ranks.size() == 1) throw;
        plot_failure = std::current_exception();
      }
    // One pass over the surfaces, each OBJ read once: placed by its outer surface as the film
    // shows it and written as .vtp, steps on each rank's threads.
    RanksMeshFarm farm(ranks);
    inspect::PvdSeriesOptions series;
    series.progress = interruptible(progress.callback());
    series.placement = [&](const inspect::MeshedStep&, const meshio::TriangleMesh* outer) {
      return rendered_offset(sc, outer);
    };
    series.threads = o.jobs;
    if (ranks.size() > 1) series.farm = &farm;
    const inspect::StepOffsets placed = inspect::write_pvd_series(simdir, report.pvd, series);
    if (plot_failure) std::rethrow_exception(plot_failure);
    if (!leader) return;
    std::map<long, std::array<double, 3>> offset_of_step;
    for (const mesh::StepRecord& step : meshes.steps) offset_of_step[step.step] = {};
    for (const auto& [step, offset] : placed) offset_of_step[step] = offset;
    // Grid runs: the solver's fields as a ParaView image series, placed like the meshes.
    if (inspect::write_field_series(simdir, out / "fields.pvd", {},
                                    [&](long step) { return offset_of_step.at(step); }) > 0)
      report.fields_pvd = out / "fields.pvd";
#if THAW_OPENVDB
    // Grid runs: the fields as OpenVDB volumes (axisymmetric ones revolved), placed like the
    // meshes.
    if (write_vdb_sequence(simdir, out / "handoff" / "vdb",
                           [&](long step) { return offset_of_step.at(step); }) > 0)
      report.handoff_vdb = out / "handoff" / "vdb";
#endif
    write_run_handoff(out, sc, rows, r.mesh_dir, meshes, "inspect");
    progress.finish();
    manifest.mark_stage_complete("inspect");
    clock.timing().items_done = 1;
  });
}

}  // namespace

RunReport run_pipeline(const RunScenario& sc, const RunOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<RunRanks> alone = opt.ranks ? nullptr : single_process();
  Run r(sc, opt, opt.ranks ? *opt.ranks : *alone);
  fingerprint_stages(r);
  check_stage_inputs(r);
  prepare_output(r);
  const std::vector<sim::InterfaceRecord> rows = simulate_stage(r);
  mesh_stage(r, rows);
  if (r.o.stage == "simulate") return finish_report(r.report, start);
  if (r.partial_meshes) r.mesh_dir = mesh::partial_steps_dir(r.simdir);
  const mesh::MeshManifest meshes =
      r.partial_meshes ? *r.partial_meshes : mesh::read_mesh_manifest(r.mesh_dir / "manifest.json");
  const long frame_count = static_cast<long>(meshes.steps.size());
  r.report.frames = static_cast<int>(frame_count);
  if (r.o.stage == "mesh") return finish_report(r.report, start);
  const bool all_frames_done = render_stage(r, meshes, rows);
  if (r.o.stage == "render" || !all_frames_done) return finish_report(r.report, start);
  on_leader(r.ranks, [&] { film_stage(r, frame_count); });  // the other ranks wait for inspect
  if (r.partial_meshes) {  // the inspect outputs are of every step's surfaces
    if (r.wanted("inspect"))
      say(r.o, stage_title(5, "inspect") +
                   ": waits for every step's meshes; run thaw run again without --frames");
    return finish_report(r.report, start);
  }
  inspect_stage(r, meshes, rows);
  return finish_report(r.report, start);
}

}  // namespace thaw::pipeline
