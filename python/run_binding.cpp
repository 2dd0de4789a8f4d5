// thaw.run: `thaw run` as a call, step for step as src/cli/command_run.cpp does it for one
// process (no MPI ranks): the same parsing of the whole scenario, the same overrides and frame
// selection, the same pipeline (src/pipeline/pipeline.h), quiet, with the progress of each stage
// given to a Python callback.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <optional>
#include <string>

#include "base/error.h"
#include "base/format/toml_table.h"
#include "python/bindings.h"
#include "python/blocking_call.h"
#include "src/pipeline/frame_selection.h"
#include "src/pipeline/pipeline.h"
#include "src/pipeline/render_overrides.h"
#include "src/pipeline/run_scenario.h"

namespace py = pybind11;

namespace thaw::python {
namespace {

struct RunArgs {
  bool builtin_default = false;   ///< the built-in scenario, unedited
  std::string text, source_name;  ///< the scenario document otherwise
  std::filesystem::path out_dir;
  std::optional<std::string> frames, stage, size;
  std::optional<long long> spp;
  std::optional<double> fps;
  bool force = false;
  int jobs = 0;
};

py::dict run(const RunArgs& a, const py::object& progress) {
  if (a.jobs < 0) throw UserError("", "jobs", "must be >= 0 (0 = all cores)");
  pipeline::RenderOverrides overrides;
  if (a.size) overrides = pipeline::parse_size_override(*a.size);
  if (a.spp) overrides.samples_per_pixel = pipeline::checked_spp_override(*a.spp);
  if (a.fps) overrides.fps = pipeline::checked_fps_override(*a.fps);
  std::optional<pipeline::FrameSelection> frames;
  if (a.frames) frames = pipeline::parse_frame_selection(*a.frames);
  if (a.stage) pipeline::check_stage_name(*a.stage);
  pipeline::RunOptions options;
  pipeline::RunScenario scenario;
  if (a.builtin_default) {
    scenario = pipeline::default_run_scenario();
    options.scenario_text = pipeline::default_run_scenario_text();
  } else {
    options.scenario_text = a.text;
    scenario = pipeline::parse_run_scenario(TomlTable::parse_string(a.text, a.source_name));
  }
  pipeline::apply_render_overrides(scenario, overrides);
  if (frames) frames->resolve(static_cast<long>(pipeline::frame_times(scenario).size()));
  options.frames = frames;
  options.stage = a.stage.value_or("");
  options.out_dir = a.out_dir;
  options.force = a.force;
  options.jobs = a.jobs;
  options.quiet = true;
  const pipeline::RunReport report =
      call_blocking([&] { return pipeline::run_pipeline(scenario, options); }, progress);
  py::dict out;
  const auto path = [](const std::filesystem::path& p) -> py::object {
    return p.empty() ? py::none() : py::cast(p);
  };
  out["film"] = path(report.film);
  out["gif"] = path(report.gif);
  out["plot"] = path(report.plot);
  out["pvd"] = path(report.pvd);
  out["handoff_scene"] = path(report.handoff_scene);
  out["fields_pvd"] = path(report.fields_pvd);
  out["handoff_vdb"] = path(report.handoff_vdb);
  out["events"] = report.events;
  py::list stages;
  for (const pipeline::StageTiming& s : report.stages) {
    py::dict d;
    d["stage"] = s.stage;
    d["seconds"] = s.seconds;
    d["skipped"] = s.skipped;
    d["items_done"] = s.items_done;
    stages.append(d);
  }
  out["stages"] = stages;
  out["frames"] = report.frames;
  out["total_seconds"] = report.total_seconds;
  return out;
}

}  // namespace

void bind_run(py::module_& m) {
  m.def(
      "run",
      [](bool builtin_default, const std::string& text, const std::string& source_name,
         const std::filesystem::path& out_dir, std::optional<std::string> frames,
         std::optional<std::string> stage, std::optional<std::string> size,
         std::optional<long long> spp, std::optional<double> fps, bool force, int jobs,
         const py::object& progress) {
        return run(RunArgs{builtin_default, text, source_name, out_dir, frames, stage, size, spp,
                           fps, force, jobs},
                   progress);
      },
      py::arg("builtin_default"), py::arg("text"), py::arg("source_name"), py::arg("out_dir"),
      py::arg("frames"), py::arg("stage"), py::arg("size"), py::arg("spp"), py::arg("fps"),
      py::arg("force"), py::arg("jobs"), py::arg("progress"));
}

}  // namespace thaw::python
