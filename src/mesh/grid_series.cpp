#include "src/mesh/grid_series.h"

#include <cstdio>
#include <optional>

#include <nlohmann/json.hpp>
#include "sim/io/grid_field.h"
#include "sim/io/interface_history.h"

#include "src/common/atomic_file.h"
#include "src/common/error.h"
#include "src/common/interrupt.h"
#include "src/mesh/grid_mesher.h"
#include "src/mesh/obj_writer.h"

namespace thaw::mesh {

namespace fs = std::filesystem;

fs::path grid_field_file(const fs::path& simdir, long step) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "step_%06ld.grid", step);
  return simdir / "fields" / buf;
}

bool is_grid_simulation_folder(const fs::path& simdir) {
  std::error_code ec;
  if (!fs::is_directory(simdir / "fields", ec)) return false;
  for (const auto& e : fs::directory_iterator(simdir / "fields", ec))
    if (e.path().extension() == ".grid") return true;
  return false;
}

namespace {

struct StepResult {
  std::optional<UserError> user_error;  // a damaged or unreadable field
  std::string error;                    // any other failure
  SurfaceRecord outer, inner;
  int cavities = 0;
  double cavity_water_fraction = 0;
  std::string remesh_problem;
  double iso_level = 0.5;
};

// A step's result as text, to pass between processes (JSON; doubles read back exactly).
nlohmann::json to_json(const SurfaceRecord& s) {
  return {{"file", s.file ? *s.file : ""},
          {"reason", s.reason},
          {"triangles", s.triangles},
          {"volume_m3", s.volume_m3},
          {"exact_volume_m3", s.exact_volume_m3}};
}

SurfaceRecord surface_from_json(const nlohmann::json& j) {
  SurfaceRecord s;
  if (!j.at("file").get<std::string>().empty()) s.file = j.at("file").get<std::string>();
  s.reason = j.at("reason").get<std::string>();
  s.triangles = j.at("triangles").get<long>();
  s.volume_m3 = j.at("volume_m3").get<double>();
  s.exact_volume_m3 = j.at("exact_volume_m3").get<double>();
  return s;
}

std::string encode(const StepResult& r) {
  nlohmann::json j = {{"error", r.error},
                      {"outer", to_json(r.outer)},
                      {"inner", to_json(r.inner)},
                      {"cavities", r.cavities},
                      {"cavity_water_fraction", r.cavity_water_fraction},
                      {"remesh_problem", r.remesh_problem},
                      {"iso_level", r.iso_level}};
  if (r.user_error)
    j["user_error"] = {r.user_error->file(), r.user_error->where(), r.user_error->problem()};
  return j.dump();
}

StepResult decode(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text);
  StepResult r;
  if (j.contains("user_error"))
    r.user_error = UserError(j["user_error"][0], j["user_error"][1], j["user_error"][2]);
  r.error = j.at("error").get<std::string>();
  r.outer = surface_from_json(j.at("outer"));
  r.inner = surface_from_json(j.at("inner"));
  r.cavities = j.at("cavities").get<int>();
  r.cavity_water_fraction = j.at("cavity_water_fraction").get<double>();
  r.remesh_problem = j.at("remesh_problem").get<std::string>();
  r.iso_level = j.at("iso_level").get<double>();
  return r;
}

void mesh_step(const fs::path& field_file, const fs::path& out_dir, long step,
               const MeshOptions& options, StepResult& r) {
  const sim::GridField f = sim::read_grid_field(field_file);
  GridMeshOptions go;
  go.edge_length_m = options.edge_length_m;
  go.normals = options.normals;
  const GridMeshResult m = mesh_grid_field(f, go);
  r.cavities = m.cavities;
  r.cavity_water_fraction = m.cavity_water_fraction;
  r.remesh_problem = m.remesh_problem;
  r.iso_level = m.iso_level;
  // The field's own volumes: ice (+ the water held in sealed cavities) inside the outer surface,
  // the water inside the inner one (what the meshes should enclose).
  double ice = 0, water = 0;
  for (int k = 0; k < f.cells[2]; ++k)
    for (int j = 0; j < f.cells[1]; ++j)
      for (int i = 0; i < f.cells[0]; ++i) {
        const std::size_t c = f.index(i, j, k);
        ice += f.ice_fraction[c] * cell_volume_m3(f, i);
        water += f.water_fraction[c] * cell_volume_m3(f, i);
      }
  for (bool inner : {false, true}) {
    const TriangleMesh& mesh = inner ? m.inner : m.outer;
    SurfaceRecord& s = inner ? r.inner : r.outer;
    if (mesh.faces.empty()) {
      s.reason = inner ? "no sealed cavity" : "no ice left";
      continue;
    }
    s.file = surface_file_name(step, inner);
    s.triangles = static_cast<long>(mesh.faces.size());
    s.volume_m3 = enclosed_volume(mesh);
    s.exact_volume_m3 = inner ? water : ice + (m.inner.faces.empty() ? 0.0 : water);
    char comment[256];
    std::snprintf(comment, sizeof comment,
                  "thaw mesh: step %ld, %s surface of a %s grid field (%d cavities)", step,
                  inner ? "inner (cavity|ice)" : "outer (ice|outside)", sim::to_string(f.geometry),
                  m.cavities);
    write_obj(out_dir / *s.file, mesh, comment);
  }
}

}  // namespace

MeshManifest mesh_grid_simulation_folder(const fs::path& simdir, const MeshOptions& requested,
                                         const ProgressCallback& progress, MeshFarm& farm) {
  validate(requested);
  const auto rows = sim::read_interfaces_csv(simdir / "interfaces.csv");
  for (const auto& row : rows)
    if (!fs::exists(grid_field_file(simdir, row.step)))
      throw UserError(grid_field_file(simdir, row.step).string(), "",
                      "file not found (a step of interfaces.csv)");
  MeshManifest manifest;
  manifest.options = requested;
  manifest.grid = true;

  const fs::path final_dir = simdir / "mesh";
  // The leader stages the folder; the other processes of a farm write their files into it.
  std::optional<StagingDirectory> staging;
  const fs::path out_dir = stage_on_leader(farm, staging, final_dir);
  const std::int64_t total = static_cast<std::int64_t>(rows.size());
  std::int64_t done = 0;
  if (progress) progress(0, total);
  // Nothing may throw out of the farmed work: every exception is caught and returned per step.
  const std::vector<std::string> texts = farm.run(
      static_cast<long>(rows.size()), requested.jobs,
      [&](long k) -> std::string {
        StepResult r;
        if (interrupt_requested()) return encode(r);  // skip the rest, throw after the loop
        const long step = rows[static_cast<std::size_t>(k)].step;
        try {
          mesh_step(grid_field_file(simdir, step), out_dir, step, requested, r);
        } catch (const UserError& e) {
          r.user_error = e;
        } catch (const std::exception& e) {
          r.error = std::string("meshing failed: ") + e.what();
        } catch (...) {
          r.error = "meshing failed";
        }
        return encode(r);
      },
      [&] {
        if (progress) progress(++done, total);
      });
  throw_if_interrupted();
  if (!farm.leader()) return manifest;  // the leader gathers and commits
  std::vector<StepResult> results;
  for (const std::string& text : texts) results.push_back(decode(text));
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const StepResult& r = results[k];
    if (r.user_error) throw *r.user_error;
    if (!r.error.empty())
      throw UserError(grid_field_file(simdir, rows[k].step).string(), "", r.error);
    StepRecord rec;
    rec.step = rows[k].step;
    rec.time_s = rows[k].time_s;
    rec.inner_radius_m = rec.inner.radius_m = rows[k].inner_radius_m;
    rec.outer_radius_m = rec.outer.radius_m = rows[k].outer_radius_m;
    rec.inner = r.inner;
    rec.outer = r.outer;
    rec.cavities = r.cavities;
    rec.cavity_water_fraction = r.cavity_water_fraction;
    rec.remesh_problem = r.remesh_problem;
    rec.iso_level = r.iso_level;
    manifest.steps.push_back(rec);
  }
  manifest.distinct_meshes = static_cast<long>(rows.size());
  write_file_atomic(staging->path() / "manifest.json", to_json(manifest).dump(1) + "\n");
  staging->commit();
  return manifest;
}

}  // namespace thaw::mesh
