// The inspect stage: the radius plot, the ParaView series, (grid runs) the OpenVDB volumes, the
// surfaces placed where the film shows them, and the scene hand-off (handoff_blender.h). Under
// MPI the steps are handed out like the mesh stage's items (each rank writes its steps' .vtp into
// the leader's staged folder), the last rank draws the plot meanwhile, and the leader commits the
// series and writes the grid runs' field exports and the hand-off. It reads every step's surfaces:
// a
// --frames process that meshed only its own leaves it to a whole run.
#include <exception>
#include <map>

#include "base/interrupt.h"
#include "base/progress.h"
#include "src/inspect/field_export.h"
#include "src/inspect/pvd_writer.h"
#include "src/inspect/radius_plot.h"
#include "src/pipeline/handoff_blender.h"
#include "src/pipeline/handoff_export.h"
#include "src/pipeline/handoff_vdb.h"
#include "src/pipeline/input_files.h"
#include "src/pipeline/stages.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;

namespace {

fs::path plot_file(const PipelineRun& r) {
  return r.out / "plot.png";
}
fs::path pvd_file(const PipelineRun& r) {
  return r.out / "meshes.pvd";
}
fs::path scene_file(const PipelineRun& r) {
  return r.out / "handoff" / "blender_scene.py";
}

StageDone inspect(PipelineRun& r, const StageCall& call) {
  const RunScenario& sc = r.sc;
  RunRanks& ranks = r.ranks;
  ProgressReporter progress(call.title, static_cast<long>(r.meshes.steps.size()), r.o.quiet);
  // The hand-off refers to the mesh stage's OBJs (handoff_blender.h): the world-space copies
  // older runs kept in handoff/obj/ go.
  if (r.leader) fs::remove_all(r.out / "handoff" / "obj");
  // The plot by the last rank (alone: this process) before it joins the steps, so that under
  // MPI it overlaps the others' steps. Its failure waits until the steps are done: the other
  // ranks wait for this one's share of them.
  std::exception_ptr plot_failure;  // rethrown as it was (a UserError stays one)
  if (ranks.rank() == ranks.size() - 1) try {
      inspect::write_radius_plot(r.simdir, plot_file(r));
    } catch (...) {
      if (ranks.size() == 1) throw;
      plot_failure = std::current_exception();
    }
  // One pass over the surfaces, each OBJ read once: placed by its outer surface as the film
  // shows it and written as .vtp, steps on each rank's threads.
  inspect::PvdSeriesOptions series;
  series.progress = interruptible(progress.callback());
  series.placement = [&](const inspect::MeshedStep&, const meshio::TriangleMesh* outer) {
    return rendered_offset(sc, outer);
  };
  series.threads = r.o.jobs;
  if (ranks.size() > 1) series.farm = &ranks;
  const inspect::StepOffsets placed = inspect::write_pvd_series(r.simdir, pvd_file(r), series);
  if (plot_failure) std::rethrow_exception(plot_failure);
  if (!r.leader) return {};
  std::map<long, std::array<double, 3>> offset_of_step;
  for (const mesh::StepRecord& step : r.meshes.steps) offset_of_step[step.step] = {};
  for (const auto& [step, offset] : placed) offset_of_step[step] = offset;
  const auto offset = [&](long step) { return offset_of_step.at(step); };
  // Grid runs: the solver's fields as a ParaView image series, placed like the meshes.
  if (inspect::write_field_series(r.simdir, r.out / "fields.pvd", {}, offset) > 0)
    r.report.fields_pvd = r.out / "fields.pvd";
#if THAW_OPENVDB
  // Grid runs: the fields as OpenVDB volumes (axisymmetric ones revolved), placed like the
  // meshes.
  if (write_vdb_sequence(r.simdir, r.out / "handoff" / "vdb", offset) > 0)
    r.report.handoff_vdb = r.out / "handoff" / "vdb";
#endif
  write_run_handoff(r.out, sc, r.rows, r.mesh_dir, r.meshes, "inspect");
  progress.finish();
  return {1};
}

}  // namespace

Stage inspect_stage() {
  Stage s;
  s.name = "inspect";
  // /5: .vtp/.vti arrays inline (Debian 12's ParaView cannot read appended data), fields placed.
  s.tag = "inspect/5";
  s.runs_on = StageRunsOn::every_rank;
  s.reads = "mesh";
  s.fingerprint = [](PipelineRun& r, ContentHash& hash) {
    const RunScenario& sc = r.sc;
    hash.add(sc.shell.rest_on_floor ? "floor" : "");
    for (double v : sc.shell.center) hash.add(v);
    hash.add(sc.shell.floor_y);
    // The scene hand-off (handoff_blender.h) sees the scene and the film's rate.
    hash.add("handoff/2").add(sc.render_text).add(sc.film.film_fps());
    add_input_files(hash, scene_input_files(sc));  // handoff/environment.hdr is made from the map
#if THAW_OPENVDB
    // A build with OpenVDB adds the volumes to an older run's (/2: axisymmetric runs' too).
    hash.add("openvdb/2");
#endif
  };
  s.outputs_exist = [](const PipelineRun& r) {
    return fs::exists(plot_file(r)) && fs::exists(pvd_file(r)) && fs::exists(scene_file(r));
  };
  s.run = inspect;
  s.waits = [](const PipelineRun& r) -> std::string {
    if (!r.partial_meshes || !r.wanted("inspect")) return "";
    return "waits for every step's meshes; run thaw run again without --frames";
  };
  s.read = [](PipelineRun& r) {
    if (!r.wanted("inspect")) return;
    r.report.plot = plot_file(r);
    r.report.pvd = pvd_file(r);
    r.report.handoff_scene = scene_file(r);
  };
  return s;
}

}  // namespace thaw::pipeline
