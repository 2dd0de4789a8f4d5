// The render stage: one frame per meshed step, handed out over the ranks one at a time (frames
// differ in cost), each written atomically and recorded as an item, so a rerun or another process
// renders only the frames not yet done. The film needs every frame of the run.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>

#include "base/atomic_file.h"
#include "base/interrupt.h"
#include "base/progress.h"
#include "render/geometry/obj_loader.h"
#include "render/image/exr_io.h"
#include "render/image/image_io.h"
#include "render/integrator/aov_pass.h"
#include "render/integrator/whitted.h"
#include "render/scene/scene.h"
#include "src/pipeline/frame_camera.h"
#include "src/pipeline/frame_label.h"
#include "src/pipeline/frame_scene.h"
#include "src/pipeline/handoff_camera.h"
#include "src/pipeline/input_files.h"
#include "src/pipeline/preview_folder.h"
#include "src/pipeline/stages.h"
#include "src/pipeline/water_budget.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;

namespace {

bool exr_frames(const RunScenario& sc) {
  return sc.film.frames_format == FilmSettings::FramesFormat::exr;
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

/// The tiles of one frame, as the renderer counts them (render/integrator/image_tile_integrator.h).
long tiles_of(const RunScenario& sc) {
  const long tile = std::max(1, render::RenderOptions{}.tile_size);
  return ((sc.scene.image.width + tile - 1) / tile) * ((sc.scene.image.height + tile - 1) / tile);
}

/// Renders frame k and writes its PNG (and EXR) atomically; nothing if interrupted. `tiles`
/// (may be empty) hears of the render's tiles as they finish.
void render_frame(const PipelineRun& r, const RunScenario& framed,
                  const std::vector<WaterBudget>& water, long k, const ProgressCallback& tiles) {
  const RunScenario& sc = r.sc;
  throw_if_interrupted();
  const mesh::StepRecord& step = r.meshes.steps[static_cast<std::size_t>(k)];
  const render::Scene scene = render::build_scene(frame_scene(
      framed, r.mesh_dir, r.meshes.geometry, step, water.at(static_cast<std::size_t>(step.step))));
  render::RenderOptions ro;
  ro.threads = r.o.jobs;
  render::RenderResult result = render::render(scene, ro, tiles);
  throw_if_interrupted();  // the render skipped its remaining tiles: write nothing
  if (exr_frames(sc)) {    // for compositing: no caption, linear, with the AOV layers
    const render::AovImage aovs = render::render_aovs(scene, r.o.jobs);
    const CameraMatrices cam =
        camera_matrices(framed.scene.camera, sc.scene.image.width, sc.scene.image.height);
    render::write_exr(r.frames_dir / (frame_name(k) + ".exr"), result.image, &aovs,
                      {sc.source_name, step.time_s, sc.scene.image.samples_per_pixel,
                       sc.scene.image.exposure, cam.world_to_camera, cam.world_to_ndc});
  }
  if (sc.film.caption) stamp_frame_caption(result.image, step.time_s, r.font.get());
  render::write_png(r.frames_dir / (frame_name(k) + ".png"), result.image, sc.scene.image.exposure,
                    8, sc.scene.image.view);
}

bool frame_files_exist(const PipelineRun& r, long k) {
  return fs::exists(r.frames_dir / (frame_name(k) + ".png")) &&
         (!exr_frames(r.sc) || fs::exists(r.frames_dir / (frame_name(k) + ".exr")));
}

/// frame_indexes, saying once that frames past the simulation's end do not exist.
std::vector<long> selected_frames(const PipelineRun& r, const StageCall& call) {
  bool cut = false;
  std::vector<long> selected = frame_indexes(r, r.frame_count, &cut);
  if (cut) {
    const long past = r.o.frames->resolve(static_cast<long>(r.times.size()))[selected.size()];
    say(r.o, call.title + ": frames from " + std::to_string(past) +
                 " on do not exist (the simulation ended early with " +
                 std::to_string(r.frame_count) + " frames)");
  }
  return selected;
}

bool every_frame_done(const PipelineRun& r) {
  for (long k = 0; k < r.frame_count; ++k)
    if (!r.manifest.item_done("render", frame_name(k))) return false;
  return true;
}

StageDone render_frames(PipelineRun& r, const StageCall& call) {
  const RunScenario& sc = r.sc;
  // The built-in camera frames the shell's largest extent over the run: one camera for all frames.
  RunScenario framed = sc;
  framed.scene.camera = run_camera(sc, r.rows, r.meshes.geometry);
  const std::vector<WaterBudget> water =
      water_budget(r.rows, r.meshes.geometry, sc.simulation.materials.ice_density_kg_m3,
                   sc.simulation.materials.water_density_kg_m3);
  if (r.leader) {
    ensure_directory(r.frames_dir);
    // What these frames are rendered with: a later run with other settings is a preview.
    write_image_settings(r.out, image_settings(sc));
    // Frames beyond the current count belong to an older, longer run.
    if (!r.subset)
      for (long k = r.frame_count; fs::exists(r.frames_dir / (frame_name(k) + ".png")); ++k) {
        fs::remove(r.frames_dir / (frame_name(k) + ".png"));
        fs::remove(r.frames_dir / (frame_name(k) + ".exr"));
      }
  }
  r.ranks.barrier();
  // The leader has (re)started the stage under this fingerprint: read it back on every rank.
  if (!r.leader) r.manifest = RunManifest(r.out / "run_manifest.json");
  const std::vector<long> selected = selected_frames(r, call);
  std::vector<long> todo;
  for (long k : selected)
    if (!(r.manifest.item_done("render", frame_name(k)) && frame_files_exist(r, k)))
      todo.push_back(k);
  const long done_before = static_cast<long>(selected.size() - todo.size());
  // One frame to render: its tiles are the progress (a big frame no longer shows "0/1, ETA ?"
  // until it ends), counted by the renderer as they finish.
  const bool by_tiles = todo.size() == 1;
  const long tiles = tiles_of(sc);
  ProgressReporter progress(
      by_tiles ? call.title + ": frame " + std::to_string(todo[0]) + ", tiles" : call.title,
      by_tiles ? tiles : static_cast<long>(selected.size()), r.o.quiet || todo.empty());
  progress.set_done(by_tiles ? 0 : done_before);
  const ProgressCallback tile_progress = by_tiles ? progress.callback() : ProgressCallback{};
  long rendered_here = 0;
  long finished = 0;
  r.ranks.run(
      static_cast<long>(todo.size()), r.o.jobs,
      [&](long i) {
        // What the frame cost, on its item's second line (bench/pipeline/mpi_scaling.sh reads
        // it): wall and process CPU seconds, and which rank.
        const long k = todo[static_cast<std::size_t>(i)];
        const auto start = std::chrono::steady_clock::now();
        const std::clock_t cpu_start = std::clock();
        render_frame(r, framed, water, k, tile_progress);
        char note[128];
        std::snprintf(
            note, sizeof note, "rank %d wall_s %.3f cpu_s %.3f", r.ranks.rank(),
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
            static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
        r.manifest.mark_item_done("render", frame_name(k), note);
        ++rendered_here;
        return std::string();
      },
      [&] {
        ++finished;
        progress.set_done(by_tiles ? tiles : done_before + finished);
      },
      WorkFarm::Grain::coarse);
  progress.finish();
  // Every frame (not only this process's) must be there before the stage is complete.
  StageDone done;
  done.items = static_cast<int>(r.leader ? todo.size() : rendered_here);
  done.complete = every_frame_done(r);
  done.skipped = todo.empty();
  return done;
}

}  // namespace

Stage render_stage() {
  Stage s;
  s.name = s.tag = "render";
  s.runs_on = StageRunsOn::farm;
  s.reads = "mesh";
  // The caption's font is an input too: DejaVu Sans, or the bitmap font if it cannot be loaded
  // (said once; loaded here for the frames).
  s.fingerprint = [](PipelineRun& r, ContentHash& hash) {
    const RunScenario& sc = r.sc;
    hash.add(sc.render_text).add(sc.film.caption ? "caption" : "");
    if (exr_frames(sc)) hash.add("frames_format=exr/2");  // /2: the camera in the header
    if (sc.film.caption) {
      std::string problem;
      r.font = CaptionFont::load(kDefaultCaptionFont, problem);
      if (r.font)
        hash.add_file(kDefaultCaptionFont);
      else
        say(r.o, "caption: " + problem + "; using the built-in bitmap font");
    }
    add_input_files(hash, scene_input_files(sc));  // the environment map, object meshes
  };
  s.outputs_exist = [](const PipelineRun& r) {
    for (long k = 0; k < r.frame_count; ++k)
      if (!frame_files_exist(r, k)) return false;
    return true;
  };
  s.run = render_frames;
  s.read = [](PipelineRun& r) { r.all_frames_done = !r.wanted("render") || every_frame_done(r); };
  return s;
}

}  // namespace thaw::pipeline
