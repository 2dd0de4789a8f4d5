#include "src/pipeline/pipeline.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "render/geometry/obj_loader.h"
#include "render/image/exr_io.h"
#include "render/image/image_io.h"
#include "render/integrator/aov_pass.h"
#include "render/integrator/whitted.h"
#include "render/scene/scene.h"
#include "sim/io/interface_history.h"
#include "sim/simulate.h"
#include "src/common/atomic_file.h"
#include "src/common/error.h"
#include "src/common/interrupt.h"
#include "src/common/progress.h"
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

}  // namespace

RunReport run_pipeline(const RunScenario& sc, const RunOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  RunReport report;
  const fs::path out = opt.out_dir;
  ensure_directory(out);
  // A run killed while writing leaves its temporary file behind; the finished outputs are intact.
  remove_stale_temporaries(out);
  const fs::path simdir = out / "sim", mesh_dir = simdir / "mesh", frames_dir = out / "frames";
  RunManifest manifest(out / "run_manifest.json");
  if (opt.force) manifest.clear();
  if (!opt.scenario_text.empty()) write_file_atomic(out / "scenario.toml", opt.scenario_text);
  if (opt.jobs > 0) omp_set_num_threads(opt.jobs);

  const std::vector<double> times = frame_times(sc);

  // 1. simulate, sampled at exactly the frame times
  ContentHash sim_hash;
  sim_hash.add("simulate").add(THAW_VERSION_STRING).add(sc.simulation_text);
  for (double t : times) sim_hash.add(t);
  {
    StageClock clock(report, "simulate");
    const bool up_to_date = manifest.begin_stage("simulate", sim_hash.hex()) &&
                            fs::exists(simdir / "interfaces.csv") && fs::exists(simdir / "summary.json");
    if (up_to_date) {
      clock.timing().skipped = true;
      say(opt, stage_title(1, "simulate") + ": up to date");
    } else {
      ProgressReporter progress(stage_title(1, "simulate"), static_cast<long>(times.size()), opt.quiet);
      const sim::SimulationResult result =
          sim::simulate(sc.simulation, times, interruptible(progress.callback()));
      StagingDirectory stage(simdir);
      sim::write_simulation_outputs(stage.path(), result);
      stage.commit();
      progress.finish();
      manifest.mark_stage_complete("simulate");
      clock.timing().items_done = static_cast<int>(result.snapshots.size());
    }
  }
  const std::vector<sim::InterfaceRecord> rows = sim::read_interfaces_csv(simdir / "interfaces.csv");

  // 2. mesh the inner and outer surface of every frame
  ContentHash mesh_hash;
  mesh_hash.add("mesh").add(sim_hash.hex()).add(sc.mesh_text);
  mesh::MeshManifest meshes;
  {
    StageClock clock(report, "mesh");
    mesh::MeshOptions options = sc.mesh;
    options.jobs = opt.jobs;
    const bool up_to_date = manifest.begin_stage("mesh", mesh_hash.hex()) && fs::exists(mesh_dir / "manifest.json");
    if (up_to_date) {
      clock.timing().skipped = true;
      say(opt, stage_title(2, "mesh") + ": up to date");
    }
    if (!up_to_date) {
      ProgressReporter progress(stage_title(2, "mesh"), static_cast<long>(2 * rows.size()), opt.quiet);
      meshes = mesh::mesh_simulation_folder(simdir, options, progress.callback());
      progress.finish();
      manifest.mark_stage_complete("mesh");
      clock.timing().items_done = static_cast<int>(meshes.steps.size());
    } else {
      meshes = mesh::read_mesh_manifest(mesh_dir / "manifest.json");
    }
  }

  // 3. render one frame per step
  ContentHash render_hash;
  render_hash.add("render").add(mesh_hash.hex()).add(sc.render_text).add(sc.film.caption ? "caption" : "");
  const bool exr_frames = sc.film.frames_format == FilmSettings::FramesFormat::exr;
  if (exr_frames) render_hash.add("frames_format=exr");
  // The caption's font: DejaVu Sans, or the bitmap font if it cannot be loaded (said once).
  std::unique_ptr<CaptionFont> font;
  if (sc.film.caption) {
    std::string problem;
    font = CaptionFont::load(kDefaultCaptionFont, problem);
    if (font)
      render_hash.add_file(kDefaultCaptionFont);
    else
      say(opt, "caption: " + problem + "; using the built-in bitmap font");
  }
  for (const auto& o : sc.scene.objects)
    if (!o.mesh_file.empty()) render_hash.add_file(o.mesh_file.is_absolute() ? o.mesh_file : sc.scene.base_dir / o.mesh_file);
  const long frame_count = static_cast<long>(meshes.steps.size());
  // The built-in camera frames the shell's largest extent over the run: one camera for all frames.
  RunScenario framed = sc;
  if (!sc.camera_set)
    framed.scene.camera =
        framing_camera(shell_extent(rows, meshes.geometry, sc.shell.center, sc.shell.rest_on_floor,
                                    sc.shell.floor_y),
                       static_cast<double>(sc.scene.image.width) / sc.scene.image.height);
  const std::vector<WaterBudget> water =
      water_budget(rows, meshes.geometry, sc.simulation.materials.ice_density_kg_m3,
                   sc.simulation.materials.water_density_kg_m3);
  report.frames = static_cast<int>(frame_count);
  {
    StageClock clock(report, "render");
    ensure_directory(frames_dir);
    const bool complete = manifest.begin_stage("render", render_hash.hex());
    // Frames beyond the current count belong to an older, longer run.
    for (long k = frame_count; fs::exists(frames_dir / (frame_name(k) + ".png")); ++k) {
      fs::remove(frames_dir / (frame_name(k) + ".png"));
      fs::remove(frames_dir / (frame_name(k) + ".exr"));
    }
    ProgressReporter progress(stage_title(3, "render"), frame_count, opt.quiet || complete);
    long done_before = 0;
    for (long k = 0; k < frame_count; ++k) {
      throw_if_interrupted();
      const fs::path png = frames_dir / (frame_name(k) + ".png");
      const fs::path exr = frames_dir / (frame_name(k) + ".exr");
      if (manifest.item_done("render", frame_name(k)) && fs::exists(png) &&
          (!exr_frames || fs::exists(exr))) {
        ++done_before;
        progress.set_done(k + 1);
        continue;
      }
      const mesh::StepRecord& step = meshes.steps[static_cast<std::size_t>(k)];
      const render::Scene scene = render::build_scene(frame_scene(
          framed, mesh_dir, meshes.geometry, step, water.at(static_cast<std::size_t>(step.step))));
      render::RenderOptions ro;
      ro.threads = opt.jobs;
      render::RenderResult result = render::render(scene, ro);
      throw_if_interrupted();  // the render skipped its remaining tiles: write nothing
      if (exr_frames) {        // for compositing: no caption, linear, with the AOV layers
        const render::AovImage aovs = render::render_aovs(scene, opt.jobs);
        render::write_exr(exr, result.image, &aovs,
                          {sc.source_name, step.time_s, sc.scene.image.samples_per_pixel,
                           sc.scene.image.exposure});
      }
      if (sc.film.caption) stamp_frame_caption(result.image, step.time_s, font.get());
      render::write_png(png, result.image, sc.scene.image.exposure);
      manifest.mark_item_done("render", frame_name(k));
      ++clock.timing().items_done;
      progress.set_done(k + 1);
    }
    progress.finish();
    manifest.mark_stage_complete("render");
    clock.timing().skipped = clock.timing().items_done == 0;
    if (complete && done_before == frame_count) say(opt, stage_title(3, "render") + ": up to date");
  }

  // 4. film
  ContentHash film_hash;
  film_hash.add("film").add(render_hash.hex()).add(sc.film_text).add(static_cast<double>(frame_count));
  report.film = out / "melt.mp4";
  if (sc.film.gif) report.gif = out / "melt.gif";
  {
    StageClock clock(report, "film");
    const bool up_to_date = manifest.begin_stage("film", film_hash.hex()) && fs::exists(report.film) &&
                            (!sc.film.gif || fs::exists(report.gif));
    if (up_to_date) {
      clock.timing().skipped = true;
      say(opt, stage_title(4, "film") + ": up to date");
    } else {
      say(opt, stage_title(4, "film") + ": encoding " + std::to_string(frame_count) + " frames with ffmpeg");
      FilmRequest request{frames_dir / "frame_%06d.png", 0, static_cast<int>(frame_count), sc.film.fps, 18};
      encode_mp4(request, report.film);
      if (sc.film.gif) encode_gif(request, report.gif);
      manifest.mark_stage_complete("film");
      clock.timing().items_done = 1;
    }
  }

  // 5. inspect: the radius plot and the ParaView series
  report.plot = out / "plot.png";
  report.pvd = out / "meshes.pvd";
  {
    StageClock clock(report, "inspect");
    const bool up_to_date = manifest.begin_stage("inspect", mesh_hash.hex()) && fs::exists(report.plot) &&
                            fs::exists(report.pvd);
    if (up_to_date) {
      clock.timing().skipped = true;
      say(opt, stage_title(5, "inspect") + ": up to date");
    } else {
      ProgressReporter progress(stage_title(5, "inspect"), frame_count, opt.quiet);
      inspect::write_pvd_series(simdir, report.pvd, interruptible(progress.callback()));
      inspect::write_radius_plot(simdir, report.plot);
      progress.finish();
      manifest.mark_stage_complete("inspect");
      clock.timing().items_done = 1;
    }
  }
  report.total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace thaw::pipeline
