// `thaw mesh SIMDIR`: CGAL surfaces (inner water|ice, outer ice|air) for every step of a
// simulation folder, written to SIMDIR/mesh/. Parsing and help text only; the work is in
// src/mesh/mesh_series.h.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "base/progress.h"
#include "src/cli/commands.h"
#include "src/mesh/mesh_series.h"

namespace thaw::cli {
namespace {

struct MeshArgs {
  std::string simdir;
  mesh::MeshOptions options;
  bool no_normals = false;
  bool quiet = false;
};

void run_mesh(MeshArgs& a, const CLI::App& sub) {
  mesh::MeshOptions options = a.options;
  options.normals = !a.no_normals;
  options.keep_distance = sub.count("--distance") > 0 || sub.count("--relative-distance") > 0;
  mesh::validate(options);
  // The reporter's total is only known once the folder is read: created on the first callback.
  std::unique_ptr<ProgressReporter> reporter;
  const mesh::MeshManifest manifest =
      mesh::mesh_simulation_folder(a.simdir, options, [&](std::int64_t done, std::int64_t total) {
        if (!reporter) reporter = std::make_unique<ProgressReporter>("mesh", total, a.quiet);
        reporter->set_done(done);
      });
  if (reporter) reporter->finish();
  long triangles = 0, files = 0;
  for (const auto& s : manifest.steps)
    for (const auto* r : {&s.inner, &s.outer})
      if (r->file) triangles += r->triangles, ++files;
  std::printf("thaw mesh: %zu steps, %ld surfaces, %ld triangles -> %s\n", manifest.steps.size(),
              files, triangles, (std::filesystem::path(a.simdir) / "mesh").string().c_str());
  // The effective options (a --triangles target is resolved only once the radii are known).
  if (manifest.grid)
    std::printf(
        "thaw mesh: grid run: marching tetrahedra, remeshed to edge %s, Taubin-smoothed "
        "(docs/mesh.md)\n",
        manifest.options.edge_length_m > 0
            ? (std::to_string(manifest.options.edge_length_m * 1e3) + " mm").c_str()
            : "= cell edge");
  else
    std::printf("thaw mesh: options: %s\n", mesh::describe(manifest.options).c_str());
  if (!manifest.steps_inner_touching_outer.empty())
    std::fprintf(
        stderr,
        "thaw mesh: warning: %zu steps have a shell too thin for the inner mesh to stay strictly "
        "inside the outer one (first: step %ld); see manifest.json\n",
        manifest.steps_inner_touching_outer.size(), manifest.steps_inner_touching_outer.front());
}

}  // namespace

void register_mesh(CLI::App& app) {
  auto args = std::make_shared<MeshArgs>();
  CLI::App* sub = app.add_subcommand(
      "mesh",
      "Mesh the inner (water|ice) and outer (ice|air) surface of every step of a simulation folder "
      "with CGAL: SIMDIR/mesh/step_NNNNNN_{inner,outer}.obj + manifest.json.");
  sub->add_option("SIMDIR", args->simdir, "simulation folder (interfaces.csv, summary.json)")
      ->required();
  sub->add_option(
         "--edge-length", args->options.edge_length_m,
         "target triangle edge length on flat or gently curved parts [m]; 0 = scene radius / 12 "
         "(2.5 mm for a 3 cm shell)")
      ->capture_default_str();
  sub->add_option(
      "--triangles", args->options.triangles,
      "target triangle count of the largest surface (replaces --edge-length; relaxes the "
      "distance bounds unless given)");
  sub->add_option("--angle", args->options.angle_deg, "minimum triangle angle [deg], <= 30")
      ->capture_default_str();
  sub->add_option(
         "--distance", args->options.distance_m,
         "maximum distance between a triangle and the true surface [m]; 0 = scene radius / 1000 "
         "(30 um for a 3 cm shell)")
      ->capture_default_str();
  sub->add_option("--relative-distance", args->options.relative_distance,
                  "distance bound as a fraction of the surface radius (slab: half lateral size)")
      ->capture_default_str();
  sub->add_option(
         "--min-radius", args->options.min_radius_m,
         "surfaces closer than this to their centre/axis/mid-plane are recorded as vanished [m]")
      ->capture_default_str();
  sub->add_option("--max-triangles", args->options.max_triangles,
                  "per-surface budget; the distance bound is relaxed to fit (0 = none)")
      ->capture_default_str();
  sub->add_flag("--no-normals", args->no_normals, "do not write vertex normals (vn)");
  sub->add_option("-j,--jobs", args->options.jobs, "worker threads (0 = all cores)")
      ->capture_default_str();
  sub->add_flag("-q,--quiet", args->quiet, "no progress display");
  sub->callback([args, sub] { run_mesh(*args, *sub); });
}

}  // namespace thaw::cli
