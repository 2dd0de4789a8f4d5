#include "src/mesh/grid_series.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <optional>

#include <nlohmann/json.hpp>
#include "sim/format/grid_field_file.h"
#include "sim/format/interface_history.h"

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/fnv_hash.h"
#include "base/interrupt.h"
#include "src/mesh/grid_mesher.h"
#include "src/mesh/obj_writer.h"
#include "thaw_version.h"

namespace thaw::mesh {

namespace fs = std::filesystem;

fs::path grid_field_file(const fs::path& simdir, long step) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "step_%06ld.grid", step);
  return simdir / "fields" / buf;
}

GridMeshOptions grid_mesh_options(const MeshOptions& options) {
  GridMeshOptions go;
  go.edge_length_m = options.edge_length_m;
  go.normals = options.normals;
  return go;
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
  bool resumed = false;  // taken from SIMDIR/mesh.partial/ (grid_series.cpp, "Resume")
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
                      {"iso_level", r.iso_level},
                      {"resumed", r.resumed}};
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
  r.resumed = j.value("resumed", false);
  return r;
}

void mesh_step(const fs::path& field_file, const fs::path& out_dir, long step,
               const MeshOptions& options, StepResult& r) {
  const sim::GridField f = sim::read_grid_field(field_file);
  const GridMeshResult m = mesh_grid_field(f, grid_mesh_options(options));
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

// Resume: as soon as a step is meshed, its surfaces (hard links to the staged files, a copy where
// links are impossible) and its result are kept in SIMDIR/mesh.partial/, so a meshing run that is
// interrupted (SIGINT, SIGTERM, a kill) keeps its finished steps and the next run meshes only the
// others, writing exactly the bytes a fresh run does (the kept files are those bytes). A step is
// taken only if the first line of its record describes exactly what was meshed: the thaw
// version, the step, the options that reach the grid mesher and the field file's size and
// FNV-1a hash (a simulation rerun into the same folder invalidates every kept step). The record
// is written last, atomically: a step whose files are kept without it is meshed again. The
// folder is removed once SIMDIR/mesh is complete (mesh_series.cpp does the same per 1D form).
std::string step_description(const fs::path& field_file, long step, const MeshOptions& o) {
  std::ifstream in(field_file, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "thaw %s grid step %ld: field %zu bytes fnv1a %016llx, edge %.17g normals %d",
                THAW_VERSION_STRING, step, bytes.size(),
                static_cast<unsigned long long>(fnv1a_64(bytes)), o.edge_length_m,
                o.normals ? 1 : 0);
  return buf;
}

fs::path kept_record(const fs::path& partial_dir, long step) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "grid_step_%06ld.json", step);
  return partial_dir / buf;
}

// `to` as the same bytes as `from`: a hard link, else a copy. Throws std::filesystem_error.
void link_or_copy(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::remove(to, ec);
  fs::create_hard_link(from, to, ec);
  if (ec) fs::copy_file(from, to, fs::copy_options::overwrite_existing);
}

// The kept result of `step` with its surfaces placed in out_dir, or nullopt (absent, another
// description, damaged: the step is meshed again).
std::optional<StepResult> take_kept_step(const fs::path& partial_dir, const fs::path& out_dir,
                                         long step, const std::string& description) {
  try {
    std::ifstream in(kept_record(partial_dir, step));
    std::string first_line, text;
    if (!std::getline(in, first_line) || first_line != "# " + description) return std::nullopt;
    std::getline(in, text);
    StepResult r = decode(text);
    if (r.user_error || !r.error.empty()) return std::nullopt;
    for (const SurfaceRecord* s : {&r.outer, &r.inner})
      if (s->file) link_or_copy(partial_dir / *s->file, out_dir / *s->file);
    r.resumed = true;
    return r;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// Keeps a meshed step for a resumed run. A cache only: a failure (disk full) is ignored.
void keep_step(const fs::path& partial_dir, const fs::path& out_dir, long step,
               const std::string& description, const StepResult& r) {
  if (r.user_error || !r.error.empty()) return;
  try {
    ensure_directory(partial_dir);
    fs::remove(kept_record(partial_dir, step));  // its files are about to change
    for (const SurfaceRecord* s : {&r.outer, &r.inner})
      if (s->file) link_or_copy(out_dir / *s->file, partial_dir / *s->file);
    write_file_atomic(kept_record(partial_dir, step), "# " + description + "\n" + encode(r) + "\n");
  } catch (const std::exception&) {
  }
}

// Step k of the series: taken from SIMDIR/mesh.partial/ or meshed (and kept). Never throws: a
// failure is the result's error.
StepResult mesh_or_resume_step(const fs::path& simdir, const fs::path& out_dir, long step,
                               const MeshOptions& options) {
  StepResult r;
  const fs::path field = grid_field_file(simdir, step), partial_dir = simdir / "mesh.partial";
  try {
    const std::string description = step_description(field, step, options);
    if (auto kept = take_kept_step(partial_dir, out_dir, step, description)) return *kept;
    mesh_step(field, out_dir, step, options, r);
    keep_step(partial_dir, out_dir, step, description, r);
  } catch (const UserError& e) {
    r.user_error = e;
  } catch (const std::exception& e) {
    r.error = std::string("meshing failed: ") + e.what();
  } catch (...) {
    r.error = "meshing failed";
  }
  return r;
}

}  // namespace

MeshManifest mesh_grid_simulation_folder(const fs::path& simdir, const MeshOptions& requested,
                                         const ProgressCallback& progress, WorkFarm& farm) {
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
        if (interrupt_requested()) return encode(StepResult{});  // skip, throw after the loop
        return encode(mesh_or_resume_step(simdir, out_dir, rows[static_cast<std::size_t>(k)].step,
                                          requested));
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
  std::error_code ec;
  fs::remove_all(simdir / "mesh.partial", ec);  // complete: nothing left to resume
  for (const StepResult& r : results) manifest.resumed_meshes += r.resumed ? 1 : 0;
  return manifest;
}

}  // namespace thaw::mesh
