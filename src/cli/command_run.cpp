// `thaw run [SCENARIO.toml] --out DIR [--force] [--jobs N] [--quiet] [--size WxH] [--spp N]`:
// simulate, mesh, render, film and inspect in one command (src/pipeline). Parsing and the closing
// summary only.
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "src/cli/commands.h"
#include "src/common/error.h"
#include "src/common/progress.h"
#include "src/pipeline/pipeline.h"
#include "src/pipeline/render_overrides.h"
#include "src/pipeline/run_scenario.h"

namespace thaw::cli {
namespace {

struct RunArgs {
  std::string scenario, out = "thaw-out";
  bool force = false, quiet = false, print_default = false;
  int jobs = 0;
  std::optional<std::string> size;
  std::optional<long long> spp;
};

void run_run(const RunArgs& a) {
  if (a.print_default) {
    std::fputs(pipeline::default_run_scenario_text().c_str(), stdout);
    return;
  }
  if (a.jobs < 0) throw UserError("", "--jobs", "must be >= 0 (0 = all cores)");
  pipeline::RenderOverrides overrides;
  if (a.size) overrides = pipeline::parse_size_override(*a.size);
  if (a.spp) overrides.samples_per_pixel = pipeline::checked_spp_override(*a.spp);
  // Parse and validate the whole scenario before any work starts.
  pipeline::RunOptions options;
  pipeline::RunScenario scenario;
  if (a.scenario.empty()) {
    scenario = pipeline::default_run_scenario();
    options.scenario_text = pipeline::default_run_scenario_text();
  } else {
    scenario = pipeline::read_run_scenario(a.scenario);
    std::ifstream in(a.scenario);
    std::stringstream text;
    text << in.rdbuf();
    options.scenario_text = text.str();
  }
  pipeline::apply_render_overrides(scenario, overrides);
  options.out_dir = a.out;
  options.force = a.force;
  options.jobs = a.jobs;
  options.quiet = a.quiet;
  const pipeline::RunReport report = pipeline::run_pipeline(scenario, options);
  if (a.quiet) return;
  std::printf("thaw run: %s -> %s (%d frames, %s)\n",
              a.scenario.empty() ? "built-in default scenario" : a.scenario.c_str(), a.out.c_str(),
              report.frames, ProgressReporter::format_duration(report.total_seconds).c_str());
  for (const auto& s : report.stages)
    std::printf("  %-9s %s\n", s.stage.c_str(),
                s.skipped ? "up to date" : ProgressReporter::format_duration(s.seconds).c_str());
  std::printf("film:  %s\n", report.film.string().c_str());
  if (!report.gif.empty()) std::printf("gif:   %s\n", report.gif.string().c_str());
  std::printf("plot:  %s\n", report.plot.string().c_str());
  std::printf("pvd:   %s\n", report.pvd.string().c_str());
}

}  // namespace

void register_run(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand(
      "run",
      "Simulate, mesh, render and film a melting ice shell in one command: DIR/melt.mp4, "
      "DIR/plot.png, DIR/meshes.pvd. Resumable: a rerun redoes only what changed. Without SCENARIO "
      "the built-in default runs (see --print-default and docs/user-guide.md).");
  cmd->add_option("scenario", args->scenario, "scenario file (TOML); omit for the built-in default");
  cmd->add_option("-o,--out", args->out, "output folder (default: thaw-out)");
  cmd->add_flag("--force", args->force, "redo every stage, even those up to date");
  cmd->add_option("-j,--jobs", args->jobs, "worker threads for meshing and rendering (0 = all cores)");
  cmd->add_flag("-q,--quiet", args->quiet, "no progress display and no summary");
  cmd->add_option(
      "--size", args->size,
      "image size WIDTHxHEIGHT [pixels] (overrides [render.image] width and height; only "
      "the frames are re-rendered)");
  cmd->add_option(
      "--spp", args->spp,
      "samples per pixel (overrides [render.image] samples_per_pixel; only the frames are "
      "re-rendered)");
  cmd->add_flag("--print-default", args->print_default, "print the built-in default scenario and exit");
  cmd->callback([args] { run_run(*args); });
}

}  // namespace thaw::cli
