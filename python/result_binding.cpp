// thaw.simulate's Result: a sim::SimulationResult owned by a Python object. interfaces, events and
// summary are small and copied; fields(step) are NumPy views of the solver's own arrays (no copy,
// read-only, their base the Result, which they keep alive). thaw.mesh meshes one step as
// `thaw mesh` does. Nothing here computes what the libraries compute.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>
#include <stdlib.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "base/error.h"
#include "base/obj_reader.h"
#include "python/bindings.h"
#include "python/blocking_call.h"
#include "sim/format/interface_history.h"
#include "sim/format/simulation_output.h"
#include "sim/simulate.h"
#include "src/mesh/grid_mesher.h"
#include "src/mesh/mesh_options.h"
#include "src/mesh/mesh_series.h"

namespace py = pybind11;

namespace thaw::python {
namespace {

/// What a Python Result holds: the library's result, and the 1D runs' liquid fractions (made on
/// first request: 1 in the water's profile points, 0 in the ice's).
struct Result {
  sim::SimulationResult result;
  std::vector<std::vector<double>> liquid_fraction;
};

/// A read-only NumPy view of `data` whose base is `owner` (which keeps the memory alive).
template <typename T>
py::array view(const py::object& owner, const T* data, std::vector<py::ssize_t> shape,
               std::vector<py::ssize_t> strides) {
  py::array a(py::dtype::of<T>(), std::move(shape), std::move(strides), data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

std::size_t checked_step(const Result& r, long step) {
  const long n = static_cast<long>(r.result.snapshots.size());
  if (step < 0) step += n;  // Python's negative indices
  if (step < 0 || step >= n)
    throw py::index_error("step " + std::to_string(step) + " out of range (the result has " +
                          std::to_string(n) + " steps)");
  return static_cast<std::size_t>(step);
}

py::dict fields(const py::object& self, long step_arg) {
  Result& r = self.cast<Result&>();
  const std::size_t step = checked_step(r, step_arg);
  py::dict out;
  if (!r.result.fields.empty()) {
    // Grid runs: cell (i, j, k) at flat index i + nx (j + ny k), viewed as [i, j, k].
    const sim::GridField& f = r.result.fields[step];
    const py::ssize_t nx = f.cells[0], ny = f.cells[1], nz = f.cells[2];
    const auto s = static_cast<py::ssize_t>(sizeof(float));
    const std::vector<py::ssize_t> shape{nx, ny, nz}, strides{s, s * nx, s * nx * ny};
    out["temperature_c"] = view(self, f.temperature_c.data(), shape, strides);
    out["liquid_fraction"] = view(self, f.water_fraction.data(), shape, strides);
    out["ice_fraction"] = view(self, f.ice_fraction.data(), shape, strides);
    // (nx, ny, nz, 3); a run without flow has no velocity: zeros, every element viewing the
    // same three (strides 0), still O(1) and still based on the Result.
    static const float kRest[3] = {0, 0, 0};
    const bool moving = f.has_velocity();
    const std::vector<py::ssize_t> shape3{nx, ny, nz, 3};
    const std::vector<py::ssize_t> strides3 =
        moving ? std::vector<py::ssize_t>{3 * s, 3 * s * nx, 3 * s * nx * ny, s}
               : std::vector<py::ssize_t>{0, 0, 0, s};
    out["velocity_m_s"] = view(self, moving ? f.velocity_m_s.data() : kRest, shape3, strides3);
    return out;
  }
  // 1D runs: the profile points (cell centres and phase boundaries), strided views.
  const auto& profile = r.result.snapshots[step].profile;
  if (r.liquid_fraction.empty()) r.liquid_fraction.resize(r.result.snapshots.size());
  std::vector<double>& liquid = r.liquid_fraction[step];
  if (liquid.size() != profile.size()) {
    liquid.resize(profile.size());
    for (std::size_t i = 0; i < profile.size(); ++i)
      liquid[i] = std::strcmp(profile[i].phase, "water") == 0 ? 1.0 : 0.0;
  }
  const auto n = static_cast<py::ssize_t>(profile.size());
  const auto stride = static_cast<py::ssize_t>(sizeof(sim::ProfilePoint));
  out["radius_m"] = view(self, profile.empty() ? nullptr : &profile[0].r_m, {n}, {stride});
  out["temperature_c"] =
      view(self, profile.empty() ? nullptr : &profile[0].temperature_c, {n}, {stride});
  out["liquid_fraction"] =
      view(self, liquid.data(), {n}, {static_cast<py::ssize_t>(sizeof(double))});
  return out;
}

py::dict interfaces(const Result& r) {
  const std::vector<sim::InterfaceRecord> rows = r.result.interface_records();
  const auto n = static_cast<py::ssize_t>(rows.size());
  py::array_t<long> step(n);
  py::array_t<double> time(n), inner(n), outer(n), liquid(n), ice(n), energy(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    const sim::InterfaceRecord& row = rows[static_cast<std::size_t>(i)];
    step.mutable_at(i) = row.step;
    time.mutable_at(i) = row.time_s;
    inner.mutable_at(i) = row.inner_radius_m;
    outer.mutable_at(i) = row.outer_radius_m;
    liquid.mutable_at(i) = row.liquid_volume_m3;
    ice.mutable_at(i) = row.ice_volume_m3;
    energy.mutable_at(i) = row.energy_balance_error;
  }
  py::dict d;  // the columns of interfaces.csv, in its order
  d["step"] = step;
  d["time_s"] = time;
  d["inner_radius_m"] = inner;
  d["outer_radius_m"] = outer;
  d["liquid_volume_m3"] = liquid;
  d["ice_volume_m3"] = ice;
  d["energy_balance_error"] = energy;
  return d;
}

py::list events(const Result& r) {
  py::list out;
  const sim::SimulationResult& s = r.result;
  for (std::size_t i = 0; i < s.events.size(); ++i) {
    py::dict e;
    e["kind"] = s.events[i].kind;
    e["time_s"] = s.events[i].time_s;
    e["radius_m"] = s.events[i].radius_m;
    if (i < s.grid_events.size()) e["position_m"] = s.grid_events[i].position_m;
    out.append(e);
  }
  return out;
}

/// A temporary folder, removed with everything in it when this goes out of scope.
class TemporaryFolder {
 public:
  TemporaryFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "thaw-python-XXXXXX").string();
    if (!::mkdtemp(pattern.data()))
      throw UserError(pattern, "",
                      "cannot make a temporary folder: " + std::string(strerror(errno)));
    m_path = pattern;
  }
  ~TemporaryFolder() {
    std::error_code ec;
    std::filesystem::remove_all(m_path, ec);
  }
  const std::filesystem::path& path() const { return m_path; }

 private:
  std::filesystem::path m_path;
};

py::tuple mesh_arrays(const std::vector<std::array<double, 3>>& vertices,
                      const std::vector<std::array<long, 3>>& triangles) {
  py::array_t<double> v({static_cast<py::ssize_t>(vertices.size()), py::ssize_t{3}});
  py::array_t<long> t({static_cast<py::ssize_t>(triangles.size()), py::ssize_t{3}});
  if (!vertices.empty()) std::memcpy(v.mutable_data(), vertices.data(), vertices.size() * 24);
  if (!triangles.empty()) std::memcpy(t.mutable_data(), triangles.data(), triangles.size() * 24);
  return py::make_tuple(v, t);
}

/// One surface of one step, meshed as `thaw mesh` meshes the run's result folder.
py::tuple mesh(const Result& r, long step_arg, const std::string& surface, int jobs) {
  const std::size_t step = checked_step(r, step_arg);
  if (surface != "outer" && surface != "inner")
    throw UserError("", "surface", "must be \"outer\" or \"inner\" (got \"" + surface + "\")");
  const bool inner = surface == "inner";
  mesh::MeshOptions options;
  options.jobs = jobs;
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<long, 3>> triangles;
  call_blocking([&] {
    if (!r.result.fields.empty()) {
      // A grid step alone: mesh_grid_field with the options grid_series.cpp takes from MeshOptions.
      mesh::GridMeshOptions go;
      go.edge_length_m = options.edge_length_m;
      go.normals = options.normals;
      const mesh::GridMeshResult m = mesh::mesh_grid_field(r.result.fields[step], go);
      const mesh::TriangleMesh& t = inner ? m.inner : m.outer;
      vertices = t.vertices;
      for (const auto& f : t.faces) triangles.push_back({f[0], f[1], f[2]});
      return 0;
    }
    // A 1D run: the series options depend on every step (the largest surface sets the scale), so
    // the result folder is written and meshed as `thaw run --frames` meshes one frame's step.
    TemporaryFolder folder;
    sim::write_simulation_outputs(folder.path(), r.result);
    const mesh::MeshManifest manifest =
        mesh::mesh_simulation_steps(folder.path(), options, {static_cast<long>(step)});
    const mesh::StepRecord& rec = manifest.steps.at(step);
    const mesh::SurfaceRecord& s = inner ? rec.inner : rec.outer;
    if (!s.file) return 0;  // vanished: empty arrays (rec's reason says why)
    const meshio::TriangleMesh m =
        meshio::read_obj(mesh::partial_steps_dir(folder.path()) / *s.file);
    vertices = m.vertices;
    for (const auto& f : m.triangles)
      triangles.push_back(
          {static_cast<long>(f[0]), static_cast<long>(f[1]), static_cast<long>(f[2])});
    return 0;
  });
  return mesh_arrays(vertices, triangles);
}

}  // namespace

void bind_result(py::module_& m) {
  py::class_<Result>(m, "Result", "The result of thaw.simulate (see help(thaw.simulate))")
      .def_property_readonly("interfaces", &interfaces,
                             "interfaces.csv as a dict of NumPy arrays, one per column (step, "
                             "time_s, inner_radius_m, outer_radius_m, liquid_volume_m3, "
                             "ice_volume_m3, energy_balance_error), one row per output time")
      .def_property_readonly("events", &events,
                             "The events (melt_onset, break_through, core_frozen, fully_melted) "
                             "as dicts: kind, time_s, radius_m (grid runs: and position_m)")
      .def(
          "summary_json", [](const Result& r) { return sim::summary_json_text(r.result); },
          "The text of summary.json, as `thaw simulate` writes it")
      .def(
          "interfaces_csv",
          [](const Result& r) { return sim::format_interfaces_csv(r.result.interface_records()); },
          "The text of interfaces.csv, as `thaw simulate` writes it")
      .def("fields", &fields, py::arg("step"),
           "fields(step) -> dict of read-only NumPy arrays viewing the result's memory (no copy; "
           "each array's .base is this Result). Grid runs: temperature_c, liquid_fraction, "
           "ice_fraction, float32, shape (nx, ny, nz) indexed [i, j, k] (axisymmetric: (nr, ny, "
           "1)), and velocity_m_s, float32, shape (nx, ny, nz, 3): the water's velocity [m/s] at "
           "the cell centres, (u_x, u_y, u_z) (axisymmetric: (u_r, u_y, 0)); zeros for a run "
           "without flow. 1D runs: radius_m, temperature_c (the profile points: cell centres and "
           "the "
           "fronts) and liquid_fraction (1 in the water, 0 in the ice), float64.")
      .def(
          "write",
          [](const Result& r, const std::filesystem::path& dir) {
            std::filesystem::create_directories(dir);
            sim::write_simulation_outputs(dir, r.result);
          },
          py::arg("dir"),
          "Writes interfaces.csv, summary.json and profiles/ or fields/ into dir, as `thaw "
          "simulate --out dir` does")
      .def_property_readonly("steps", [](const Result& r) { return r.result.snapshots.size(); })
      .def_property_readonly("ended_early", [](const Result& r) { return r.result.ended_early; })
      .def_property_readonly("wall_time_s", [](const Result& r) { return r.result.wall_time_s; })
      .def_property_readonly(
          "grid",
          [](const Result& r) -> py::object {
            if (r.result.fields.empty()) return py::none();
            const sim::GridField& f = r.result.fields.front();
            py::dict g;
            g["geometry"] = sim::to_string(f.geometry);
            g["cells"] = f.cells;
            g["origin_m"] = f.origin_m;
            g["spacing_m"] = f.spacing_m;
            return g;
          },
          "Grid runs: geometry, cells, origin_m, spacing_m of the fields; None for 1D runs");

  m.def(
      "simulate",
      [](const sim::Scenario& scenario, const py::object& progress) {
        auto r = std::make_unique<Result>();
        r->result = call_blocking(
            [&] {
              // As `thaw simulate`: a (quiet) progress bar whose callback is the safe point
              // where an interrupt ends the run.
              ProgressReporter bar("simulate",
                                   static_cast<std::int64_t>(sim::output_times(scenario).size()),
                                   /*quiet=*/true);
              return sim::simulate(scenario, interruptible(bar.callback()));
            },
            progress);
        return r;
      },
      py::arg("scenario"), py::arg("progress") = py::none());
  m.def("mesh", &mesh, py::arg("result"), py::arg("step"), py::arg("surface") = "outer",
        py::arg("jobs") = 0);
}

}  // namespace thaw::python
