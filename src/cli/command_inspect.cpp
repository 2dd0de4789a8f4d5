// `thaw inspect PATH`: checks a mesh (an OBJ) or every mesh of a simulation folder, and on request
// writes a ParaView collection, a screenshot and a radius/volume plot. Parsing and help only.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "base/error.h"
#include "base/interrupt.h"
#include "base/obj_reader.h"
#include "base/output_file.h"
#include "base/progress.h"
#include "sim/format/grid_field_file.h"
#include "src/cli/commands.h"
#include "src/inspect/field_line.h"
#include "src/inspect/mesh_report.h"
#include "src/inspect/pvd_writer.h"
#include "src/inspect/radius_plot.h"
#include "src/inspect/screenshot.h"
#include "src/inspect/simulation_folder.h"

namespace thaw::cli {
namespace fs = std::filesystem;
namespace {

struct InspectArgs {
  std::string path;
  bool json = false;
  bool quiet = false;
  std::string pvd, screenshot, plot;
  std::optional<long> step;
  /// --over-line "x0,y0,z0;x1,y1,z1" --samples N [--csv]
  std::string over_line;
  std::optional<long> samples;
  bool csv = false;
};

/// Largest --samples: a line of ten million points is already 1 GB of CSV.
constexpr long kMaxLineSamples = 10'000'000;

/// --over-line: the fields of one step sampled along a line, as CSV on stdout.
void run_over_line(const InspectArgs& a) {
  const auto ends = inspect::parse_line_ends(a.over_line);
  if (!a.samples)
    throw UserError(a.path, "--samples", "--over-line needs --samples N (N >= 2 points)");
  if (*a.samples < 2 || *a.samples > kMaxLineSamples)
    throw UserError(a.path, "--samples",
                    std::to_string(*a.samples) + " points: at least 2 (the two ends), at most " +
                        std::to_string(kMaxLineSamples));
  if (!a.pvd.empty() || !a.screenshot.empty() || !a.plot.empty() || a.json)
    throw UserError(a.path, "--over-line",
                    "prints CSV only: it cannot be combined with --json, --pvd, --screenshot or "
                    "--plot");
  std::error_code ec;
  if (!fs::is_directory(a.path, ec))
    throw UserError(a.path, "--over-line", "needs a simulation folder (fields/step_*.grid)");
  const fs::path file = inspect::field_file_of_step(a.path, a.step);
  const sim::GridField field = sim::read_grid_field(file);
  std::vector<inspect::LineSample> samples;
  try {
    samples = inspect::sample_over_line(field, ends[0], ends[1], *a.samples);
  } catch (const UserError& e) {
    throw UserError(file.string(), e.where(), e.problem());  // the points outside name the file
  }
  std::cout << inspect::format_line_csv(samples);
  std::cout.flush();
}

/// The output names, before any work: a .pvd, PNG pictures (a missing folder is created).
void check_outputs(const InspectArgs& a) {
  if (!a.pvd.empty()) check_output_file(a.pvd, {".pvd"});
  if (!a.screenshot.empty()) check_output_file(a.screenshot, {".png"});
  if (!a.plot.empty()) check_output_file(a.plot, {".png"});
}

void run_inspect(const InspectArgs& a) {
  if (!a.over_line.empty()) return run_over_line(a);
  if (a.samples) throw UserError(a.path, "--samples", "only applies with --over-line");
  if (a.csv) throw UserError(a.path, "--csv", "only applies with --over-line");
  check_outputs(a);
  const fs::path path(a.path);
  std::error_code ec;
  if (!fs::exists(path, ec)) throw UserError(a.path, "", "no such file or folder");
  if (fs::is_directory(path, ec)) {
    if (!inspect::is_simulation_folder(path))
      throw UserError(a.path, "",
                      "not a simulation folder (no interfaces.csv) and not an OBJ file");
    const inspect::SimulationFolder folder = inspect::read_simulation_folder(path);
    std::vector<inspect::StepReport> reports;
    {
      ProgressReporter progress("inspect", static_cast<std::int64_t>(folder.steps.size()),
                                a.quiet || folder.steps.size() < 2);
      reports = inspect::inspect_simulation(folder, interruptible(progress.callback()));
    }
    if (a.json)
      std::cout << inspect::to_json(reports).dump(2) << "\n";
    else
      std::cout << inspect::format_table(folder, reports);
    std::cout.flush();
    if (!a.pvd.empty()) {
      ProgressReporter progress("pvd", static_cast<std::int64_t>(folder.steps.size()),
                                a.quiet || folder.steps.size() < 2);
      inspect::write_pvd_series(path, a.pvd, interruptible(progress.callback()));
      progress.finish();
      if (!a.quiet) std::fprintf(stderr, "thaw inspect: wrote %s\n", a.pvd.c_str());
    }
    if (!a.screenshot.empty()) {
      inspect::write_simulation_screenshot(path, a.screenshot, a.step);
      if (!a.quiet) std::fprintf(stderr, "thaw inspect: wrote %s\n", a.screenshot.c_str());
    }
    if (!a.plot.empty()) {
      inspect::write_radius_plot(path, a.plot);
      if (!a.quiet) std::fprintf(stderr, "thaw inspect: wrote %s\n", a.plot.c_str());
    }
    return;
  }
  if (!a.plot.empty())
    throw UserError(a.path, "--plot", "needs a simulation folder (interfaces.csv), not one OBJ");
  if (a.step) throw UserError(a.path, "--step", "only applies to a simulation folder");
  const inspect::MeshReport report = inspect::inspect_obj(path);
  if (a.json)
    std::cout << inspect::to_json(report).dump(2) << "\n";
  else
    std::cout << inspect::format_table(report);
  std::cout.flush();
  if (!a.pvd.empty()) {
    inspect::PvdWriter writer(a.pvd);
    const inspect::TriangleMesh mesh = meshio::read_obj(path);
    writer.add(0, 0.0, inspect::SurfacePart::outer, &mesh);
    writer.commit();
    if (!a.quiet) std::fprintf(stderr, "thaw inspect: wrote %s\n", a.pvd.c_str());
  }
  if (!a.screenshot.empty()) {
    inspect::write_obj_screenshot(path, a.screenshot);
    if (!a.quiet) std::fprintf(stderr, "thaw inspect: wrote %s\n", a.screenshot.c_str());
  }
}

}  // namespace

void register_inspect(CLI::App& app) {
  auto args = std::make_shared<InspectArgs>();
  CLI::App* cmd = app.add_subcommand(
      "inspect",
      "Check meshes with VTK: an OBJ file, or every step of a simulation folder (SIMDIR with "
      "interfaces.csv and mesh/manifest.json). Prints vertices, triangles, boundary and "
      "non-manifold edges, orientation, volume, area, bounding box, triangle angles and aspect "
      "ratios. --screenshot and --plot need an X display; without one thaw starts Xvfb.");
  cmd->add_option("PATH", args->path, "an OBJ file or a simulation folder")->required();
  cmd->add_flag("--json", args->json, "print the report as JSON (an array of steps for a folder)");
  cmd->add_option("--pvd", args->pvd,
                  "write a ParaView collection OUT.pvd (+ OUT_vtp/ with one .vtp per step and "
                  "surface; timestep = simulated seconds)")
      ->type_name("OUT.pvd");
  cmd->add_option("--screenshot", args->screenshot,
                  "write an off-screen rendering (edges shown; outer surface translucent) to PNG")
      ->type_name("OUT.png");
  cmd->add_option("--plot", args->plot,
                  "write inner/outer radius and volumes against time to PNG (simulation folder)")
      ->type_name("OUT.png");
  cmd->add_option("--step", args->step,
                  "with --screenshot on a folder: draw this step only (default: up to 4 steps); "
                  "with --over-line: the step sampled (default: the last)")
      ->type_name("N");
  cmd->add_option("--over-line", args->over_line,
                  "sample a grid run's fields at --samples points from (x0,y0,z0) to (x1,y1,z1) "
                  "[m, the scenario's coordinates; axisymmetric: x is the radius], linear "
                  "between cell centres, and print CSV: " +
                      std::string(inspect::kLineCsvHeader))
      ->type_name("\"x0,y0,z0;x1,y1,z1\"");
  cmd->add_option("--samples", args->samples, "with --over-line: points on the line (>= 2)")
      ->type_name("N");
  cmd->add_flag("--csv", args->csv, "with --over-line: print CSV (its only format)");
  cmd->add_flag("-q,--quiet", args->quiet, "no progress or 'wrote' lines on stderr");
  cmd->callback([args] { run_inspect(*args); });
}

}  // namespace thaw::cli
