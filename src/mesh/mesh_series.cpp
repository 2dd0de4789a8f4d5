#include "src/mesh/mesh_series.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/fnv_hash.h"
#include "base/format/mesh_manifest.h"
#include "base/interrupt.h"
#include "base/obj_reader.h"
#include "base/outcome.h"
#include "sim/format/interface_history.h"
#include "src/mesh/geodesic_sphere.h"
#include "src/mesh/grid_series.h"
#include "src/mesh/obj_writer.h"
#include "src/mesh/similar_surface.h"
#include "src/mesh/surface_mesher.h"
#include "thaw_version.h"

namespace thaw::mesh {

namespace fs = std::filesystem;

std::string surface_file_name(long step, bool inner) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "step_%06ld_%s.obj", step, inner ? "inner" : "outer");
  return buf;
}

namespace {

// One surface to mesh: decided sequentially before the parallel loop.
struct Task {
  std::size_t step_index = 0;
  bool inner = true;
  ShellShape shape;
  SurfaceCriteria criteria;
};

// What a task reports back (written by exactly one thread, read after the loop).
struct TaskResult {
  std::string error;  // "" if fine
  /// The surface could not be written (disk full ...): the UserError's problem, "" if written.
  /// Not a meshing failure: its message names the file and gives no meshing hint.
  std::string write_problem;
  long triangles = 0;
  double volume_m3 = 0;
  // Containment of the inner mesh in the outer one, through f(x) = dist(x, C) to the convex core
  // C the two surfaces share. The inner mesh lies in {f <= max_core_distance} (its vertices do,
  // and that set is convex). f is convex, so on an outer triangle T with centroid p,
  // f(x) >= f(p) + grad f(p) . (x - p) >= f(p) + min over T's vertices v of grad f(p) . (v - p):
  // min_face_core_distance is that lower bound minimised over the outer triangles. If it exceeds
  // max_core_distance, no outer triangle meets the inner mesh's convex neighbourhood, which is
  // connected and holds the core, hence lies strictly inside the closed outer mesh. (Facet
  // planes are no use here: on the cylindrical parts a Delaunay mesh is not exactly convex.)
  double max_core_distance = 0;
  double min_face_core_distance = 0;
};

void measure(const ShellShape& shape, const TriangleMesh& m, TaskResult& r) {
  r.triangles = static_cast<long>(m.faces.size());
  r.volume_m3 = enclosed_volume(m);
  r.max_core_distance = 0;
  for (const auto& v : m.vertices)
    r.max_core_distance = std::max(r.max_core_distance, shape.signed_distance(v) + shape.radius_m);
  r.min_face_core_distance = std::numeric_limits<double>::infinity();
  for (const auto& f : m.faces) {
    const Vec3 &a = m.vertices[f[0]], &b = m.vertices[f[1]], &c = m.vertices[f[2]];
    const Vec3 p{(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3};
    const double fp = shape.signed_distance(p) + shape.radius_m;
    const Vec3 g = shape.outward_normal(p);
    double lowest = 0;
    for (const Vec3* v : {&a, &b, &c})
      lowest = std::min(
          lowest, g[0] * ((*v)[0] - p[0]) + g[1] * ((*v)[1] - p[1]) + g[2] * ((*v)[2] - p[2]));
    r.min_face_core_distance = std::min(r.min_face_core_distance, fp > 0 ? fp + lowest : 0.0);
  }
}

// A task's result as text, to pass between processes (17 digits: doubles read back exactly).
std::string encode(const TaskResult& r) {
  if (!r.error.empty()) return "E" + r.error;
  if (!r.write_problem.empty()) return "W" + r.write_problem;
  char buf[128];
  std::snprintf(buf, sizeof buf, "%ld %.17g %.17g %.17g", r.triangles, r.volume_m3,
                r.max_core_distance, r.min_face_core_distance);
  return buf;
}

TaskResult decode(const std::string& text) {
  TaskResult r;
  if (text.empty() || text[0] == 'E') {
    r.error = text.empty() ? "no result" : text.substr(1);
    return r;
  }
  if (text[0] == 'W') {
    r.write_problem = text.substr(1);
    return r;
  }
  char* end = nullptr;
  r.triangles = std::strtol(text.c_str(), &end, 10);
  r.volume_m3 = std::strtod(end, &end);
  r.max_core_distance = std::strtod(end, &end);
  r.min_face_core_distance = std::strtod(end, &end);
  return r;
}

// The unit mesh multiplied by `scale_m` (the radius of `shape`, or 1 without reuse), with the
// outward normals of `shape` (the surface it now approximates) if wanted, into `m` (its storage
// reused: obj_writer.h's ObjBuffers says why).
void scaled_copy(const TriangleMesh& unit, double scale_m, const ShellShape& shape, bool normals,
                 TriangleMesh& m) {
  m.faces = unit.faces;
  m.vertices.clear();
  for (const auto& v : unit.vertices)
    m.vertices.push_back({v[0] * scale_m, v[1] * scale_m, v[2] * scale_m});
  m.normals.clear();
  if (normals)
    for (const auto& v : m.vertices) m.normals.push_back(shape.outward_normal(v));
}

void validate_geometry(const sim::ShellGeometry& g, const fs::path& summary) {
  if (g.geometry == sim::Geometry::planar && !(g.lateral_size_m > 0))
    throw UserError(summary.string(), "parameters.shell.lateral_size_m",
                    "must be > 0 for a planar shell, got " + std::to_string(g.lateral_size_m));
}

// Resume: every distinct mesh is kept in SIMDIR/mesh.partial/ as soon as it is made, so a
// meshing run that is interrupted (SIGINT, SIGTERM, a kill) keeps its finished surfaces and the
// next run meshes only the others. The file's first line is the full description of what was
// meshed (form and options, thaw version); a file is used only if that line matches exactly.
// Vertices are written with 17 digits and read back bit for bit (base/obj_reader.h), so a resumed
// run writes exactly the bytes a fresh one does. The folder is removed once SIMDIR/mesh is
// complete.
std::string form_description(const SimilarSurface& f, const MeshOptions& unit_options,
                             int geodesic) {
  // Every input of the mesher: the shape (radius too: without reuse of similar surfaces the
  // "unit" shape is the surface itself), the criteria and the options; which mesher.
  const ShellShape& u = f.unit_shape;
  const SurfaceCriteria& c = f.unit_criteria;
  char buf[360];
  std::snprintf(buf, sizeof buf,
                "thaw %s unit mesh: geometry %d radius %.17g core %.17g angle %.17g size %.17g "
                "distance %.17g mesher %s %d options ",
                THAW_VERSION_STRING, static_cast<int>(u.geometry), u.radius_m, u.core_half_size_m,
                c.facet_angle_deg, c.facet_size_m, c.facet_distance_m,
                geodesic > 0 ? "geodesic" : "Mesh_3", geodesic);
  return buf + to_json(unit_options).dump();
}

fs::path form_cache_file(const fs::path& partial_dir, const std::string& description) {
  char name[40];
  std::snprintf(name, sizeof name, "form_%016llx.obj",
                static_cast<unsigned long long>(fnv1a_64(description)));
  return partial_dir / name;
}

/// The cached unit mesh for `description`, or nullopt (absent, another description, unreadable).
std::optional<TriangleMesh> load_cached_form(const fs::path& file, const std::string& description) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return std::nullopt;
  std::ifstream in(file);
  std::string first_line;
  std::getline(in, first_line);
  if (first_line != "# " + description) return std::nullopt;
  try {
    const meshio::TriangleMesh read = meshio::read_obj(file);
    if (!read.normal_triangles.empty()) return std::nullopt;  // kept without normals
    return from_file_mesh(read);
  } catch (const UserError&) {
    return std::nullopt;  // damaged: mesh it again
  }
}

/// Keeps a finished unit mesh for a resumed run. A cache only: a failure to write (disk full) is
/// not the meshing's failure and is ignored. Meshes with normals are not kept (their 9-digit
/// normals would not read back bit for bit).
void store_cached_form(const fs::path& file, const std::string& description,
                       const TriangleMesh& m) {
  if (!m.normals.empty()) return;
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  const Outcome kept = Outcome::of([&] { write_obj(file, m, description); });
  if (kept.kind() != Outcome::Kind::user) kept.rethrow();  // a write failure only is ignored
}

// The inputs of a 1D series: the steps of interfaces.csv and the shell of summary.json.
struct SeriesInput {
  std::vector<sim::InterfaceRecord> rows;
  sim::ShellGeometry geometry;
};

SeriesInput read_series_input(const fs::path& simdir) {
  const fs::path summary = simdir / "summary.json";
  SeriesInput in{sim::read_interfaces_csv(simdir / "interfaces.csv"),
                 sim::read_shell_geometry(summary)};
  validate_geometry(in.geometry, summary);
  return in;
}

// The requested options resolved for the series: the largest outer surface sets the scene radius
// (the scale of the automatic edge length and distance) and the area the triangle target is for.
MeshOptions series_options(const MeshOptions& requested, const SeriesInput& in) {
  double largest_area = 0, scene_radius = 0;
  for (const auto& r : in.rows) {
    const ShellShape outer = ShellShape::from_geometry(in.geometry, r.outer_radius_m);
    largest_area = std::max(largest_area, outer.area());
    scene_radius = std::max(scene_radius, outer.bounding_radius());
  }
  if (!(scene_radius > 0)) scene_radius = 1;  // nothing to mesh: any positive scale will do
  return resolve_triangle_target(resolve_scene(requested, scene_radius), largest_area);
}

// A step's record with the reasons its surfaces are not meshed, if any ("" = meshed).
StepRecord step_record(const sim::InterfaceRecord& row, const MeshOptions& options) {
  StepRecord rec;
  rec.step = row.step;
  rec.time_s = row.time_s;
  rec.inner_radius_m = rec.inner.radius_m = row.inner_radius_m;
  rec.outer_radius_m = rec.outer.radius_m = row.outer_radius_m;
  if (!(row.outer_radius_m > row.inner_radius_m)) {
    rec.outer.reason = rec.inner.reason = "no ice left (outer_radius_m == inner_radius_m)";
    return rec;
  }
  if (row.inner_radius_m <= 0)
    rec.inner.reason = "no liquid core left (inner_radius_m == 0)";
  else if (row.inner_radius_m < options.min_radius_m)
    rec.inner.reason = "inner radius below min_radius_m";
  if (row.outer_radius_m < options.min_radius_m)
    rec.outer.reason = "outer radius below min_radius_m";
  return rec;
}

// The surface `inner` of step `step_index` as a task, or nullopt (with the reason recorded) if it
// is too thin to mesh.
std::optional<Task> surface_task(std::size_t step_index, bool inner, const sim::ShellGeometry& g,
                                 const MeshOptions& options, StepRecord& rec) {
  SurfaceRecord& s = inner ? rec.inner : rec.outer;
  Task t;
  t.step_index = step_index;
  t.inner = inner;
  t.shape = ShellShape::from_geometry(g, s.radius_m);
  if (too_thin_to_mesh(t.shape, options)) {
    s.reason = "slab too thin for its lateral size to mesh within max_triangles";
    return std::nullopt;
  }
  t.criteria = criteria_for(t.shape, options);
  if (!inner && rec.inner.reason.empty()) {
    // Keep the outer mesh's facets off the inner surface: a facet deviates inward by at most its
    // distance bound, so a bound below the shell thickness keeps the inner mesh strictly inside.
    // Refining costs triangles ~ 1 / distance; stop at 1/8 of the normal bound.
    const double shell = rec.outer_radius_m - rec.inner_radius_m;
    const double d = t.criteria.facet_distance_m;
    t.criteria = criteria_for(t.shape, options, std::max(std::min(d, 0.5 * shell), d / 8));
  }
  check_triangle_count(t.shape, t.criteria);  // before any work: a typo must not run for ever
  s.file = surface_file_name(rec.step, inner);
  s.distance_bound_m = t.criteria.facet_distance_m;
  s.exact_volume_m3 = t.shape.volume();
  return t;
}

// The manifest's step records and the surfaces to mesh, in step order (inner before outer).
std::vector<Task> plan_surfaces(const SeriesInput& in, const MeshOptions& options,
                                MeshManifest& manifest) {
  std::vector<Task> tasks;
  for (std::size_t i = 0; i < in.rows.size(); ++i) {
    StepRecord rec = step_record(in.rows[i], options);
    for (bool inner : {true, false})
      if ((inner ? rec.inner : rec.outer).reason.empty())
        if (auto t = surface_task(i, inner, in.geometry, options, rec)) tasks.push_back(*t);
    manifest.steps.push_back(rec);
  }
  return tasks;
}

// Similar surfaces (equal canonical forms, similar_surface.h) share one mesh made at unit scale;
// in a sphere series with the default relative distance bound that is nearly every surface.
struct FormPlan {
  std::vector<SimilarSurface> forms;     // the distinct meshes to make
  std::vector<std::size_t> form_of;      // per task: its form
  std::vector<double> scale_of;          // per task: the form's unit mesh times this [m]
  std::vector<std::string> description;  // per form: form_description (the resume key)
  /// Per form: the geodesic frequency of a sphere (geodesic_sphere.h), 0: meshed by Mesh_3.
  std::vector<int> geodesic;
};

// Spheres are geodesic polyhedra (the least frequency meeting their criteria: a closed form, the
// one serial step of a sphere series made cheap); everything else, and a sphere whose criteria no
// frequency meets, is meshed by Mesh_3.
int geodesic_frequency_of(const SimilarSurface& f) {
  if (f.unit_shape.geometry != sim::Geometry::sphere || f.unit_shape.core_half_size_m != 0)
    return 0;
  return geodesic_frequency(f.unit_shape.radius_m, f.unit_criteria);
}

FormPlan group_similar_surfaces(const std::vector<Task>& tasks, const MeshOptions& options,
                                const MeshOptions& unit_options) {
  FormPlan plan;
  plan.form_of.resize(tasks.size());
  plan.scale_of.assign(tasks.size(), 1.0);
  std::map<decltype(SimilarSurface{}.key()), std::size_t> index;
  for (std::size_t k = 0; k < tasks.size(); ++k) {
    if (!options.reuse_similar) {  // every surface meshed as it is (benchmarks compare)
      plan.form_of[k] = plan.forms.size();
      plan.forms.push_back(SimilarSurface{tasks[k].shape, tasks[k].criteria, 1.0});
      continue;
    }
    const SimilarSurface f = similar_surface(tasks[k].shape, tasks[k].criteria);
    const auto [pos, added] = index.try_emplace(f.key(), plan.forms.size());
    if (added) plan.forms.push_back(f);
    plan.form_of[k] = pos->second;
    plan.scale_of[k] = f.scale_m;
  }
  for (const SimilarSurface& f : plan.forms) {
    plan.geodesic.push_back(geodesic_frequency_of(f));
    plan.description.push_back(form_description(f, unit_options, plan.geodesic.back()));
  }
  return plan;
}

// (done, total) of the series, reported to the caller's callback (on the leader, sequentially).
struct SeriesProgress {
  const ProgressCallback& callback;
  std::int64_t done = 0, total = 0;
  void report() const {
    if (callback) callback(done, total);
  }
  void one_done() {
    ++done;
    report();
  }
};

// The unit mesh of every form, or the reason it failed.
struct FormMeshes {
  std::vector<TriangleMesh> unit;
  std::vector<std::string> error;  // "" if fine
  std::vector<char> have;          // 1 once unit[k] is there
  long resumed = 0;                // taken from SIMDIR/mesh.partial/
  /// Forms meshed by this process, with CGAL's surface for their checks (check_form), which run
  /// after the form is shared: until then, unit[k] is not checked.
  std::vector<std::optional<UncheckedSurface>> unchecked;
};

// Meshes kept by an earlier, interrupted run (read before meshing: a mesh made in this run is
// never taken for one of them).
void take_kept_forms(const FormPlan& plan, const fs::path& partial_dir, FormMeshes& m) {
  for (std::size_t k = 0; k < plan.forms.size(); ++k)
    if (auto kept = load_cached_form(form_cache_file(partial_dir, plan.description[k]),
                                     plan.description[k])) {
      m.unit[k] = std::move(*kept);
      m.have[k] = 1;
      ++m.resumed;
    }
}

// Meshes form k and (if `keep`) keeps it for a resumed run and the other processes, before its
// checks (check_form, in write_surfaces: the form is the one serial step of a 1D series, so its
// checks run while the surfaces are copied from it); a failure is stored in m.error[k], never
// thrown.
void mesh_form(const FormPlan& plan, std::size_t k, const MeshOptions& unit_options,
               const fs::path& partial_dir, FormMeshes& m, bool keep = true) {
  try {
    const SimilarSurface& form = plan.forms[k];
    if (const int n = plan.geodesic[k]; n > 0) {
      m.unit[k] = geodesic_sphere(form.unit_shape.radius_m, n);  // checked like a kept form
    } else {
      UncheckedSurface surface =
          mesh_surface_unchecked(form.unit_shape, form.unit_criteria, unit_options);
      m.unit[k] = surface.mesh();
      m.unchecked[k] = std::move(surface);
    }
    if (keep)
      store_cached_form(form_cache_file(partial_dir, plan.description[k]), plan.description[k],
                        m.unit[k]);
    m.have[k] = 1;
  } catch (const std::exception& e) {
    m.error[k] = e.what();
  } catch (...) {
    m.error[k] = "unknown failure";
  }
}

// Meshes the forms not kept, spread over the farm. A form another process meshed reaches this
// one through the resume cache (kept since the farm returned); one that cannot be read back (a
// failed cache write) is meshed again here.
void mesh_missing_forms(const FormPlan& plan, const MeshOptions& unit_options, int jobs,
                        const fs::path& partial_dir, WorkFarm& farm, SeriesProgress& progress,
                        FormMeshes& m) {
  std::vector<std::size_t> to_mesh;
  for (std::size_t k = 0; k < plan.forms.size(); ++k)
    if (!m.have[k]) to_mesh.push_back(k);
  // A geodesic form takes ~2 ms. With fewer forms than processes and all of them geodesic (the
  // default film: one), a farm would have the other processes wait for them and then read them
  // back from the cache (~1 ms each): every process builds its missing ones itself (the same
  // bytes), the leader keeping them for a resumed run. Decided from the plan, the same on every
  // process (the forms kept may differ: another process may have stored one meanwhile), so that
  // they all take the farm or none does.
  const bool all_geodesic =
      std::all_of(plan.geodesic.begin(), plan.geodesic.end(), [](int n) { return n > 0; });
  if (farm.processes() > 1 && all_geodesic &&
      plan.forms.size() < static_cast<std::size_t>(farm.processes())) {
    for (const std::size_t k : to_mesh) {
      if (interrupt_requested()) {
        m.error[k] = "interrupted";  // thrown after the surfaces, as from the farm
        continue;
      }
      mesh_form(plan, k, unit_options, partial_dir, m, farm.leader());
      if (farm.leader()) progress.one_done();
    }
    return;
  }
  // Nothing may throw out of the farmed work: every failure is stored or returned as text.
  const std::vector<std::string> results = farm.run(
      static_cast<long>(to_mesh.size()), jobs,
      [&](long i) -> std::string {
        const std::size_t k = to_mesh[static_cast<std::size_t>(i)];
        if (interrupt_requested()) return "interrupted";  // thrown after the loop
        mesh_form(plan, k, unit_options, partial_dir, m);
        return m.error[k];
      },
      [&] { progress.one_done(); });
  for (std::size_t i = 0; i < to_mesh.size(); ++i)
    if (!results[i].empty()) m.error[to_mesh[i]] = results[i];
  for (std::size_t k = 0; k < plan.forms.size(); ++k) {
    if (m.have[k] || !m.error[k].empty() || interrupt_requested()) continue;
    if (auto kept = load_cached_form(form_cache_file(partial_dir, plan.description[k]),
                                     plan.description[k])) {
      m.unit[k] = std::move(*kept);
      m.have[k] = 1;
    } else {
      mesh_form(plan, k, unit_options, partial_dir, m);
    }
  }
}

// Task k's surface: its form's unit mesh scaled, with the normals of its own shape, measured and
// written to out_dir. Never throws: a failure is the result's error.
TaskResult write_surface(const Task& t, const FormPlan& plan, std::size_t k, const FormMeshes& m,
                         const MeshManifest& manifest, const MeshOptions& options,
                         const fs::path& out_dir) {
  TaskResult r;
  const std::size_t form = plan.form_of[k];
  try {
    if (!m.error[form].empty()) throw MeshError(m.error[form]);
    // One surface after another on this thread: the same storage for each (ObjBuffers).
    thread_local TriangleMesh mesh;
    thread_local ObjBuffers buffers;
    scaled_copy(m.unit[form], plan.scale_of[k], t.shape, options.normals, mesh);
    measure(t.shape, mesh, r);
    const StepRecord& rec = manifest.steps[t.step_index];
    char comment[256];
    std::snprintf(comment, sizeof comment,
                  "thaw mesh: step %ld, %s surface of a %s, radius %.17g m", rec.step,
                  t.inner ? "inner (water|ice)" : "outer (ice|air)",
                  sim::to_string(t.shape.geometry), t.shape.radius_m);
    write_obj(out_dir / surface_file_name(rec.step, t.inner), mesh, comment, buffers);
  } catch (const UserError& e) {  // only writing throws these here
    r.write_problem = e.problem();
  } catch (const std::exception& e) {
    r.error = e.what();
  } catch (...) {
    r.error = "unknown failure";
  }
  return r;
}

// The checks of mesh_surface (surface_mesher.h) on form k: "" or the problem. On CGAL's own
// surface where this process meshed the form, otherwise (another process meshed it, or it was
// kept by an interrupted run before its checks) on the mesh read back. A form that failed to
// mesh has nothing to check: its surfaces carry that failure.
std::string check_form(std::size_t k, FormMeshes& m) {
  if (!m.error[k].empty() || !m.have[k] || interrupt_requested()) return "";
  try {
    std::string problem =
        m.unchecked[k] ? m.unchecked[k]->check() : check_closed_manifold_outward(m.unit[k]);
    m.unchecked[k].reset();  // CGAL's surface is large and needed no more
    return problem;
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "unknown failure";
  }
}

// Every form checked and every surface written, spread over the farm: first the forms' checks,
// then the surfaces in task order (the output is the same for any thread count). On the leader
// the surfaces' results, a surface of a form that failed its checks failing as mesh_surface's
// MeshError made it fail (its file, written meanwhile, goes with the staged folder); on the
// others empty ones.
std::vector<TaskResult> write_surfaces(const std::vector<Task>& tasks, const FormPlan& plan,
                                       FormMeshes& m, const MeshManifest& manifest,
                                       const MeshOptions& options, const fs::path& out_dir,
                                       WorkFarm& farm, SeriesProgress& progress) {
  const long checks = static_cast<long>(plan.forms.size());
  const std::vector<std::string> texts = farm.run(
      checks + static_cast<long>(tasks.size()), options.jobs,
      [&](long item) -> std::string {
        if (item < checks) return check_form(static_cast<std::size_t>(item), m);
        if (interrupt_requested()) {
          TaskResult skipped;
          skipped.error = "interrupted";  // thrown after the loop
          return encode(skipped);
        }
        const auto i = static_cast<std::size_t>(item - checks);
        return encode(write_surface(tasks[i], plan, i, m, manifest, options, out_dir));
      },
      [&] { progress.one_done(); });
  std::vector<TaskResult> results;
  if (!farm.leader()) return results;
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    const std::string& problem = texts[plan.form_of[i]];
    if (!problem.empty()) {
      results.emplace_back().error = problem;
      continue;
    }
    results.push_back(decode(texts[static_cast<std::size_t>(checks) + i]));
  }
  return results;
}

// Takes each surface's triangle count and volume into the manifest, in step order (so the first
// error reported does not depend on scheduling); a failed surface is a UserError.
void record_surfaces(const std::vector<Task>& tasks, const std::vector<TaskResult>& results,
                     const fs::path& final_dir, MeshManifest& manifest) {
  for (std::size_t k = 0; k < tasks.size(); ++k) {
    const Task& t = tasks[k];
    StepRecord& rec = manifest.steps[t.step_index];
    if (!results[k].write_problem.empty())
      throw UserError((final_dir / surface_file_name(rec.step, t.inner)).string(), "",
                      results[k].write_problem);
    if (!results[k].error.empty())
      throw UserError(
          (final_dir / surface_file_name(rec.step, t.inner)).string(), "",
          "meshing failed: " + results[k].error +
              " (try a smaller edge length or distance bound: edge_length_m, distance_m)");
    SurfaceRecord& s = t.inner ? rec.inner : rec.outer;
    s.triangles = results[k].triangles;
    s.volume_m3 = results[k].volume_m3;
  }
}

// Whether each step's inner mesh is strictly inside its outer mesh (TaskResult's bound), the
// thinnest shell for which it is, and the steps too thin for it; a thick shell whose meshes
// touch is a UserError.
void check_containment(const std::vector<Task>& tasks, const std::vector<TaskResult>& results,
                       const fs::path& final_dir, MeshManifest& manifest) {
  std::vector<const TaskResult*> inner_of(manifest.steps.size(), nullptr),
      outer_of(manifest.steps.size(), nullptr);
  for (std::size_t k = 0; k < tasks.size(); ++k)
    (tasks[k].inner ? inner_of : outer_of)[tasks[k].step_index] = &results[k];
  for (std::size_t i = 0; i < manifest.steps.size(); ++i) {
    if (!inner_of[i] || !outer_of[i]) continue;
    StepRecord& rec = manifest.steps[i];
    const bool inside = inner_of[i]->max_core_distance < outer_of[i]->min_face_core_distance;
    rec.inner_inside_outer = inside;
    const double shell = rec.outer_radius_m - rec.inner_radius_m;
    if (inside) {
      if (!manifest.thinnest_contained_shell_m || shell < *manifest.thinnest_contained_shell_m)
        manifest.thinnest_contained_shell_m = shell;
      continue;
    }
    // CGAL bounds the deviation at facet circumcentres; elsewhere on a capsule or slab facet it
    // was measured up to ~1.2x that, so only a shell over twice the bound must be contained.
    if (shell > 2 * rec.outer.distance_bound_m)
      throw UserError((final_dir / surface_file_name(rec.step, false)).string(), "",
                      "inner mesh not strictly inside the outer mesh although the shell (" +
                          std::to_string(shell) + " m) is over twice the distance bound");
    manifest.steps_inner_touching_outer.push_back(rec.step);
  }
}

}  // namespace

namespace {

constexpr const char* kNotMeshedHere =
    "not meshed: thaw run --frames meshes only its frames' steps (a whole run meshes the rest)";

// Keeps the tasks of the steps at `step_indexes` (positions in manifest.steps); every other
// step's surfaces lose their files and say why.
void keep_only_steps(const std::vector<long>& step_indexes, std::vector<Task>& tasks,
                     MeshManifest& manifest) {
  std::vector<char> wanted(manifest.steps.size(), 0);
  for (const long k : step_indexes)
    if (k >= 0 && static_cast<std::size_t>(k) < wanted.size())
      wanted[static_cast<std::size_t>(k)] = 1;
  std::erase_if(tasks, [&](const Task& t) { return !wanted[t.step_index]; });
  for (std::size_t i = 0; i < manifest.steps.size(); ++i) {
    if (wanted[i]) continue;
    for (SurfaceRecord* s : {&manifest.steps[i].inner, &manifest.steps[i].outer})
      if (s->file) {
        s->file.reset();
        s->reason = kNotMeshedHere;
      }
  }
}

// mesh_simulation_folder, or with `only` mesh_simulation_steps.
MeshManifest mesh_series(const fs::path& simdir, const MeshOptions& requested,
                         const ProgressCallback& progress, WorkFarm& farm,
                         const std::vector<long>* only) {
  // A run killed outright (SIGKILL, a lost node) leaves its staged folder and temporaries: the
  // leader removes those of dead processes before staging (the other processes of a farm write
  // nothing before the staged folder is shared). Not for a part of a run: other processes (on
  // other machines, whose process ids mean nothing here) may be writing into the folder.
  if (farm.leader() && !only) remove_stale_temporaries(simdir);
  if (is_grid_simulation_folder(simdir))
    return mesh_grid_simulation_folder(simdir, requested, progress, farm);
  validate(requested);
  const SeriesInput in = read_series_input(simdir);
  MeshManifest manifest;
  manifest.options = series_options(requested, in);
  manifest.geometry = in.geometry;
  const MeshOptions& options = manifest.options;
  std::vector<Task> tasks = plan_surfaces(in, options, manifest);
  if (only) keep_only_steps(*only, tasks, manifest);

  const fs::path final_dir = simdir / "mesh", partial_dir = simdir / "mesh.partial";
  // The leader stages the folder; the other processes of a farm write their files into it. A
  // part of a run writes its steps' files (each atomically) beside the kept forms instead.
  std::optional<StagingDirectory> staging;
  fs::path out_dir;
  if (only) {
    out_dir = partial_steps_dir(simdir);
    manifest.partial = true;
    std::error_code ec;
    fs::create_directories(out_dir, ec);  // concurrent processes may create it too
    if (!fs::is_directory(out_dir))
      throw UserError(out_dir.string(), "", "cannot create folder: " + ec.message());
  } else {
    out_dir = stage_on_leader(farm, staging, final_dir);
  }

  MeshOptions unit_options = options;
  unit_options.normals = false;  // each surface takes the normals of its own shape
  const FormPlan plan = group_similar_surfaces(tasks, options, unit_options);
  manifest.distinct_meshes = static_cast<long>(plan.forms.size());
  FormMeshes meshes{std::vector<TriangleMesh>(plan.forms.size()),
                    std::vector<std::string>(plan.forms.size()),
                    std::vector<char>(plan.forms.size(), 0), 0,
                    std::vector<std::optional<UncheckedSurface>>(plan.forms.size())};
  take_kept_forms(plan, partial_dir, meshes);
  // Work items: the forms to mesh, each form's checks, each surface.
  SeriesProgress counter{progress, meshes.resumed,
                         static_cast<std::int64_t>(2 * plan.forms.size() + tasks.size())};
  counter.report();
  mesh_missing_forms(plan, unit_options, options.jobs, partial_dir, farm, counter, meshes);
  const std::vector<TaskResult> results =
      write_surfaces(tasks, plan, meshes, manifest, options, out_dir, farm, counter);
  throw_if_interrupted();
  if (!farm.leader()) return manifest;  // the leader gathers, checks and commits

  const fs::path& named_dir = only ? out_dir : final_dir;
  record_surfaces(tasks, results, named_dir, manifest);
  check_containment(tasks, results, named_dir, manifest);
  manifest.resumed_meshes = meshes.resumed;
  if (only) return manifest;  // kept for the whole run, which completes it
  write_file_atomic(out_dir / "manifest.json", to_json(manifest).dump(1) + "\n");
  staging->commit();
  std::error_code ec;
  fs::remove_all(partial_dir, ec);  // complete: nothing left to resume
  return manifest;
}

}  // namespace

fs::path partial_steps_dir(const fs::path& simdir) {
  return simdir / "mesh.partial" / "steps";
}

MeshManifest mesh_simulation_folder(const fs::path& simdir, const MeshOptions& requested,
                                    const ProgressCallback& progress, WorkFarm& farm) {
  return mesh_series(simdir, requested, progress, farm, nullptr);
}

MeshManifest mesh_simulation_steps(const fs::path& simdir, const MeshOptions& requested,
                                   const std::vector<long>& step_indexes,
                                   const ProgressCallback& progress, WorkFarm& farm) {
  return mesh_series(simdir, requested, progress, farm, &step_indexes);
}

nlohmann::ordered_json to_json(const MeshManifest& m) {
  nlohmann::ordered_json j;
  j["format"] = "thaw-mesh/1";
  j["options"] = to_json(m.options);
  nlohmann::ordered_json g;
  if (m.grid) {
    g["geometry"] = "grid";
    g["frame"] = "the grid field's coordinates (axisymmetric fields revolved about the y axis)";
  } else {
    g["geometry"] = sim::to_string(m.geometry.geometry);
    switch (m.geometry.geometry) {
      case sim::Geometry::sphere:
        g["frame"] = "spheres centred at the origin";
        break;
      case sim::Geometry::cylinder:
        g["length_m"] = m.geometry.length_m;
        g["frame"] = "capsules centred at the origin, axis along z, tube |z| <= length_m / 2";
        break;
      case sim::Geometry::planar:
        g["lateral_size_m"] = m.geometry.lateral_size_m;
        g["planar_symmetric"] = m.geometry.planar_symmetric;
        g["frame"] = "slabs |x| <= radius, flat faces |y|,|z| <= lateral_size_m / 2, rounded edges";
        break;
    }
  }
  j["geometry"] = g;
  j["thinnest_contained_shell_m"] = m.thinnest_contained_shell_m
                                        ? nlohmann::ordered_json(*m.thinnest_contained_shell_m)
                                        : nlohmann::ordered_json(nullptr);
  j["steps_inner_touching_outer"] = m.steps_inner_touching_outer;
  j["distinct_meshes"] = m.distinct_meshes;
  nlohmann::ordered_json steps = nlohmann::ordered_json::array();
  for (const auto& s : m.steps) {
    nlohmann::ordered_json e;
    e["step"] = s.step;
    e["time_s"] = s.time_s;
    e["inner_radius_m"] = s.inner_radius_m;
    e["outer_radius_m"] = s.outer_radius_m;
    for (const char* key : {"inner", "outer"}) {
      const SurfaceRecord& r = key[0] == 'i' ? s.inner : s.outer;
      e[key] = r.file ? nlohmann::ordered_json(*r.file) : nlohmann::ordered_json(nullptr);
    }
    e["inner_triangles"] = s.inner.triangles;
    e["outer_triangles"] = s.outer.triangles;
    for (const std::string key : {"inner", "outer"}) {
      const SurfaceRecord& r = key == "inner" ? s.inner : s.outer;
      if (r.file) {
        e[key + "_volume_m3"] = r.volume_m3;
        e[key + "_exact_volume_m3"] = r.exact_volume_m3;
        e[key + "_distance_bound_m"] = r.distance_bound_m;
      } else {
        e[key + "_reason"] = r.reason;
      }
    }
    e["inner_inside_outer"] = s.inner_inside_outer ? nlohmann::ordered_json(*s.inner_inside_outer)
                                                   : nlohmann::ordered_json(nullptr);
    if (m.grid) {
      e["cavities"] = s.cavities;
      e["cavity_water_fraction"] = s.cavity_water_fraction;
      e["remesh_problem"] = s.remesh_problem;
      e["iso_level"] = s.iso_level;
    }
    steps.push_back(e);
  }
  j["steps"] = steps;
  return j;
}

MeshManifest read_mesh_manifest(const std::filesystem::path& manifest_json) {
  const meshio::MeshManifestFile file = meshio::read_mesh_manifest(manifest_json);
  MeshManifest m;
  // The frame the surfaces are in: a resumed run must place and measure them as the first did.
  m.grid = file.geometry == "grid";
  if (!file.geometry.empty() && !m.grid) sim::parse_geometry(file.geometry, m.geometry.geometry);
  m.geometry.length_m = file.length_m;
  m.geometry.lateral_size_m = file.lateral_size_m;
  m.geometry.planar_symmetric = file.planar_symmetric;
  for (const meshio::ManifestStep& e : file.steps) {
    StepRecord s;
    s.step = e.step;
    s.time_s = e.time_s;
    s.inner_radius_m = s.inner.radius_m = e.inner_radius_m;
    s.outer_radius_m = s.outer.radius_m = e.outer_radius_m;
    s.inner.file = e.inner;
    s.outer.file = e.outer;
    s.inner.triangles = e.inner_triangles;
    s.outer.triangles = e.outer_triangles;
    m.steps.push_back(std::move(s));
  }
  return m;
}

}  // namespace thaw::mesh
