// `thaw run [SCENARIO.toml] --out DIR [--force] [--jobs N] [--quiet] [--size WxH] [--spp N]
// [--preview-dir P] [--fps F] [--frames N,A-B,A:B:S] [--stage NAME]`: simulate, mesh, render, film
// and inspect in one command (src/pipeline). Parsing and the closing summary only.
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "base/error.h"
#include "base/format/toml_table.h"
#include "base/outcome.h"
#include "base/progress.h"
#include "base/text_file.h"
#include "src/cli/commands.h"
#include "src/pipeline/frame_selection.h"
#include "src/pipeline/pipeline.h"
#include "src/pipeline/rank_agreement.h"
#include "src/pipeline/render_overrides.h"
#include "src/pipeline/run_ranks.h"
#include "src/pipeline/run_scenario.h"

namespace thaw::cli {
namespace {

struct RunArgs {
  std::string scenario, out = "thaw-out";
  bool force = false, quiet = false, print_default = false;
  int jobs = 0;
  std::optional<std::string> size;
  std::optional<long long> spp;
  std::optional<double> fps;
  std::optional<std::string> frames, stage, preview_dir;
};

void run_alone_or_as_rank(const RunArgs& a, pipeline::RunRanks* ranks);

void run_run(const RunArgs& a) {
  if (a.print_default) {
    std::fputs(pipeline::default_run_scenario_text().c_str(), stdout);
    return;
  }
  // Under mpirun every rank runs this; the leader speaks. A failure is the leader's word (all
  // ranks hear it, the leader prints it); a rank that alone failed prints its own.
  std::unique_ptr<pipeline::RunRanks> ranks = pipeline::mpi_ranks_if_launched();
  if (!ranks || ranks->size() == 1) return run_alone_or_as_rank(a, ranks.get());
  const Outcome mine = Outcome::of([&] { run_alone_or_as_rank(a, ranks.get()); });
  pipeline::end_on_ranks(ranks, mine);
}

void run_alone_or_as_rank(const RunArgs& a, pipeline::RunRanks* ranks) {
  const bool speaks = !ranks || ranks->leader();
  if (a.jobs < 0) throw UserError("", "--jobs", "must be >= 0 (0 = all cores)");
  pipeline::RenderOverrides overrides;
  if (a.size) overrides = pipeline::parse_size_override(*a.size);
  if (a.spp) overrides.samples_per_pixel = pipeline::checked_spp_override(*a.spp);
  if (a.fps) overrides.fps = pipeline::checked_fps_override(*a.fps);
  std::optional<pipeline::FrameSelection> frames;
  if (a.frames) frames = pipeline::parse_frame_selection(*a.frames);
  if (a.stage) pipeline::check_stage_name(*a.stage);
  // Parse and validate the whole scenario before any work starts.
  pipeline::RunOptions options;
  pipeline::RunScenario scenario;
  if (a.scenario.empty()) {
    scenario = pipeline::default_run_scenario();
    options.scenario_text = pipeline::default_run_scenario_text();
  } else {
    // read once: the text parsed is the text fingerprinted (a pipe reads only once)
    options.scenario_text = read_text_file(a.scenario, "a TOML file", kMaxTomlFileBytes);
    scenario =
        pipeline::parse_run_scenario(TomlTable::parse_string(options.scenario_text, a.scenario));
  }
  pipeline::apply_render_overrides(scenario, overrides);
  // A range past the film's last frame is an error before any work starts.
  if (frames) frames->resolve(static_cast<long>(pipeline::frame_times(scenario).size()));
  options.frames = frames;
  options.stage = a.stage.value_or("");
  options.out_dir = a.out;
  if (a.preview_dir) options.preview_dir = *a.preview_dir;
  options.force = a.force;
  options.jobs = a.jobs;
  options.quiet = a.quiet;
  options.ranks = ranks;
  const pipeline::RunReport report = pipeline::run_pipeline(scenario, options);
  if (a.quiet || !speaks) return;
  std::printf("thaw run: %s -> %s (%d frames, %s)\n",
              a.scenario.empty() ? "built-in default scenario" : a.scenario.c_str(),
              report.preview_dir.empty() ? a.out.c_str() : report.preview_dir.c_str(),
              report.frames, ProgressReporter::format_duration(report.total_seconds).c_str());
  for (const auto& e : report.events) std::printf("  %s\n", e.c_str());
  for (const auto& s : report.stages)
    std::printf("  %-9s %s\n", s.stage.c_str(),
                s.skipped ? "up to date" : ProgressReporter::format_duration(s.seconds).c_str());
  for (const auto& [label, path] : {std::pair{"film:  ", report.film},
                                    {"gif:   ", report.gif},
                                    {"plot:  ", report.plot},
                                    {"pvd:   ", report.pvd},
                                    {"scene: ", report.handoff_scene},
                                    {"fields:", report.fields_pvd},
                                    {"vdb:   ", report.handoff_vdb}})
    if (!path.empty()) std::printf("%s%s\n", label, path.string().c_str());
  if (!report.preview_dir.empty())
    std::printf("preview: %s (the finals in %s are kept; --force replaces them)\n",
                report.preview_dir.c_str(), a.out.c_str());
}

}  // namespace

void register_run(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand(
      "run",
      "Simulate, mesh, render and film a melting ice shell in one command: DIR/melt.mp4, "
      "DIR/plot.png, DIR/meshes.pvd. Resumable: a rerun redoes only what changed. Without SCENARIO "
      "the built-in default runs (see --print-default and docs/user-guide.md).");
  cmd->add_option("scenario", args->scenario,
                  "scenario file (TOML); omit for the built-in default");
  cmd->add_option("-o,--out", args->out, "output folder (default: thaw-out)");
  cmd->add_flag("--force", args->force,
                "redo every stage, even those up to date; with --size / --spp, replace the "
                "folder's final frames and film rather than writing a preview");
  cmd->add_option("-j,--jobs", args->jobs,
                  "worker threads for meshing and rendering (0 = all cores)");
  cmd->add_flag("-q,--quiet", args->quiet, "no progress display and no summary");
  cmd->add_option(
      "--size", args->size,
      "image size WIDTHxHEIGHT [pixels] (overrides [render.image] width and height; only "
      "the frames are re-rendered; if DIR holds frames of another size, this run is a preview in "
      "DIR/preview/ and keeps them)");
  cmd->add_option(
      "--spp", args->spp,
      "samples per pixel (overrides [render.image] samples_per_pixel; only the frames are "
      "re-rendered; a preview in DIR/preview/ if DIR holds frames of other settings)");
  cmd->add_option("--preview-dir", args->preview_dir,
                  "run as a preview in this folder, starting from DIR's simulation and meshes and "
                  "keeping DIR's frames and film (default with --size / --spp other than the "
                  "finals': DIR/preview)");
  cmd->add_option("--fps", args->fps,
                  "frame rate of melt.mp4 (overrides [film] fps for playback only: the frames' "
                  "simulated times stay, so only the film is re-encoded)");
  cmd->add_option("--frames", args->frames,
                  "render only these frames, numbered from 0: N, FIRST-LAST or FIRST:LAST:STEP, "
                  "or a list of them (e.g. 17,36 or 10-20 or 3:40:2 or 0-4,30) for a look at "
                  "a few frames, Slurm job arrays or GNU parallel; the film is made "
                  "once every frame is rendered (docs/pipeline.md)");
  cmd->add_option("--stage", args->stage,
                  "run only this stage: simulate, mesh, render, film or inspect (the stages "
                  "before it must be up to date)");
  cmd->add_flag("--print-default", args->print_default,
                "print the built-in default scenario and exit");
  cmd->callback([args] { run_run(*args); });
}

}  // namespace thaw::cli
