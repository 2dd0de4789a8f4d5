// Benchmarks of the CGAL mesher (src/mesh) against the issue-4 targets, and against VTK's
// vtkFlyingEdges3D, the fast marching-cubes baseline users know. Figures: docs/benchmarks.md.
//   Sphere40k        default criteria, sphere radius chosen so that it has ~40k triangles
//                    (target: < 1 s on one core)
//   Series100/jobs/reuse  100 steps of a 3 cm sphere shell (200 surfaces) with 1 and 2 threads,
//                    each surface meshed on its own (reuse 0; target: 2 threads >= 1.8x the
//                    1-thread rate) and similar surfaces meshed once and scaled (reuse 1, the
//                    default; issue 10: "every step of a sphere is the same mesh scaled")
//   GridCube         one step of the hollow ice cube of data/scenarios/ice_cube.toml (4 cm box,
//                    2.4 cm water-filled cavity, 1 mm cells, edges rounded 2 mm as after a few
//                    minutes of melting) meshed from its GridField (src/mesh/grid_mesher.h) at a
//                    1 mm edge (issue 11 target: a 3D step in at most 1 s)
//   FlyingEdges      the 3 cm sphere's signed distance sampled on the smallest N^3 grid whose
//                    marching-cubes volume error is at most the CGAL default mesh's, then
//                    vtkFlyingEdges3D; time includes sampling (reported separately too)
#include <benchmark/benchmark.h>
#include <vtkFloatArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkMassProperties.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkTriangleFilter.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <string>

#include "base/atomic_file.h"
#include "base/obj_reader.h"
#include "sim/format/interface_history.h"
#include "src/mesh/geodesic_sphere.h"
#include "src/mesh/grid_mesher.h"
#include "src/mesh/mesh_series.h"
#include "src/mesh/obj_writer.h"
#include "src/mesh/surface_mesher.h"
#include "tests/src/mesh/grid_field_samples.h"

namespace {
using namespace thaw;
namespace fs = std::filesystem;

mesh::ShellShape sphere(double r) {
  mesh::ShellShape s;
  s.radius_m = r;
  return s;
}

void Sphere40k(benchmark::State& state) {
  const mesh::ShellShape s = sphere(0.07);  // default edge 2.5 mm: ~39k triangles at R = 7 cm
  const mesh::MeshOptions o;
  std::size_t triangles = 0;
  for (auto _ : state) {
    const mesh::TriangleMesh m = mesh::mesh_surface(s, o);
    triangles = m.faces.size();
    benchmark::DoNotOptimize(m.vertices.data());
  }
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["triangles_per_s"] = benchmark::Counter(
      static_cast<double>(triangles), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(Sphere40k)->Unit(benchmark::kMillisecond)->Iterations(3);

// The serial part of the default film's mesh stage (issue 13): its one CGAL form, the unit sphere
// every one of its 103 surfaces is scaled from (relative distance bound 1e-3, the size bound
// redundant: similar_surface.h), taken apart in thread CPU time (load-independent):
//   form_ms        mesh_surface_unchecked: Mesh_3 and the extraction of the boundary, the part
//                  no other rank can start before (it is what they copy)
//   checks_ms      UncheckedSurface::check (closed, manifold, Euler, self-intersection,
//                  orientation): run while the other ranks copy the form
//   cache_write_ms the form written to the resume cache (17-digit OBJ), how the other ranks get it
//   cache_read_ms  reading it back, on each other rank
//   copy_write_ms  one surface: the form scaled, with its normals, written (103 of them)
void DefaultFilmForm(benchmark::State& state) {
  const mesh::ShellShape unit = sphere(1.0);
  mesh::SurfaceCriteria c;
  c.facet_angle_deg = 30;
  c.facet_size_m = 2;
  c.facet_distance_m = 1e-3;
  mesh::MeshOptions o;
  o.normals = false;
  const fs::path file = fs::temp_directory_path() / "thaw_bench_mesh_form.obj";
  const auto cpu_ms = [] {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
  };
  double form_ms = 0, check_ms = 0, write_ms = 0, read_ms = 0, copy_ms = 0;
  std::size_t triangles = 0;
  for (auto _ : state) {
    const double t0 = cpu_ms();
    const mesh::UncheckedSurface form = mesh::mesh_surface_unchecked(unit, c, o);
    const double t1 = cpu_ms();
    benchmark::DoNotOptimize(form.check());
    const double t2 = cpu_ms();
    mesh::write_obj(file, form.mesh(), "form");
    const double t3 = cpu_ms();
    const mesh::TriangleMesh back = mesh::from_file_mesh(meshio::read_obj(file));
    const double t4 = cpu_ms();
    mesh::TriangleMesh copy = back;
    for (auto& v : copy.vertices)
      for (double& x : v) x *= 0.03;
    for (const auto& v : copy.vertices) copy.normals.push_back(sphere(0.03).outward_normal(v));
    mesh::write_obj(file, copy, "copy");
    const double t5 = cpu_ms();
    form_ms += t1 - t0;
    check_ms += t2 - t1;
    write_ms += t3 - t2;
    read_ms += t4 - t3;
    copy_ms += t5 - t4;
    triangles = form.mesh().faces.size();
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["form_ms"] = form_ms / n;
  state.counters["checks_ms"] = check_ms / n;
  state.counters["cache_write_ms"] = write_ms / n;
  state.counters["cache_read_ms"] = read_ms / n;
  state.counters["copy_write_ms"] = copy_ms / n;
  fs::remove(file);
}
BENCHMARK(DefaultFilmForm)->Unit(benchmark::kMillisecond)->Iterations(5);

// The form the mesh stage makes for the default film since the sphere mesher
// (geodesic_sphere.h): the frequency search and the mesh, then the checks (CGAL, run as the
// first item of the surface farm), in thread CPU time like DefaultFilmForm's Mesh_3.
void DefaultFilmGeodesicForm(benchmark::State& state) {
  const mesh::SurfaceCriteria c{30, 2, 1e-3};
  const auto cpu_ms = [] {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
  };
  double form_ms = 0, check_ms = 0;
  std::size_t triangles = 0;
  for (auto _ : state) {
    const double t0 = cpu_ms();
    const mesh::TriangleMesh form = mesh::geodesic_sphere(1, mesh::geodesic_frequency(1, c));
    const double t1 = cpu_ms();
    benchmark::DoNotOptimize(mesh::check_closed_manifold_outward(form));
    const double t2 = cpu_ms();
    form_ms += t1 - t0;
    check_ms += t2 - t1;
    triangles = form.faces.size();
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["form_ms"] = form_ms / n;
  state.counters["checks_ms"] = check_ms / n;
}
BENCHMARK(DefaultFilmGeodesicForm)->Unit(benchmark::kMillisecond)->Iterations(20);

fs::path series_folder() {
  const fs::path dir = fs::temp_directory_path() / "thaw_bench_mesh_series";
  fs::create_directories(dir);
  std::vector<sim::InterfaceRecord> rows;
  for (int i = 0; i < 100; ++i) {
    sim::InterfaceRecord r;
    r.step = i;
    r.time_s = 60.0 * i;
    r.inner_radius_m = 0.010 + 0.018 * i / 99.0;  // the liquid core grows 1 -> 2.8 cm
    r.outer_radius_m = 0.030 - 0.001 * i / 99.0;  // the outside ablates 3 -> 2.9 cm
    rows.push_back(r);
  }
  sim::write_interfaces_csv(dir / "interfaces.csv", rows);
  write_file_atomic(
      dir / "summary.json",
      R"({"parameters":{"simulation":{"geometry":"sphere"},"shell":{},"inner_boundary":{"kind":"heated"}}})");
  return dir;
}

void Series100(benchmark::State& state) {
  const fs::path dir = series_folder();
  mesh::MeshOptions o;
  o.jobs = static_cast<int>(state.range(0));
  o.reuse_similar = state.range(1) != 0;
  long triangles = 0, distinct = 0;
  for (auto _ : state) {
    const mesh::MeshManifest m = mesh::mesh_simulation_folder(dir, o);
    triangles = 0;
    for (const auto& s : m.steps) triangles += s.inner.triangles + s.outer.triangles;
    distinct = m.distinct_meshes;
  }
  state.counters["distinct_meshes"] = static_cast<double>(distinct);
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["triangles_per_s"] = benchmark::Counter(
      static_cast<double>(triangles), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["steps_per_s"] =
      benchmark::Counter(100, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(Series100)
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({1, 1})
    ->Args({2, 1})
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

void GridCube(benchmark::State& state) {
  using mesh::testing::rounded_box;
  const sim::GridField f = mesh::testing::sample_cartesian(
      [](double x, double y, double z) { return rounded_box(x, y, z, 0.02, 0.02, 0.02, 0.002); },
      [](double x, double y, double z) { return rounded_box(x, y, z, 0.012, 0.012, 0.012, 0.0); },
      0.022, 0.001, 3);
  mesh::GridMeshOptions o;
  o.edge_length_m = 0.001;
  std::size_t triangles = 0;
  for (auto _ : state) {
    const mesh::GridMeshResult m = mesh::mesh_grid_field(f, o);
    triangles = m.outer.faces.size() + m.inner.faces.size();
    benchmark::DoNotOptimize(m.outer.vertices.data());
  }
  state.counters["triangles"] = static_cast<double>(triangles);
  state.counters["cells"] = static_cast<double>(f.cell_count());
}
BENCHMARK(GridCube)->Unit(benchmark::kMillisecond)->Iterations(3);

struct McResult {
  double volume_error = 0, sample_s = 0, extract_s = 0;
  long triangles = 0;
};

McResult marching_cubes(const mesh::ShellShape& s, int n) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  const double half = 1.1 * s.radius_m, h = 2 * half / (n - 1);
  vtkNew<vtkImageData> grid;
  grid->SetDimensions(n, n, n);
  grid->SetOrigin(-half, -half, -half);
  grid->SetSpacing(h, h, h);
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfTuples(static_cast<vtkIdType>(n) * n * n);
  vtkIdType id = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        values->SetValue(
            id++,
            static_cast<float>(s.signed_distance({-half + i * h, -half + j * h, -half + k * h})));
  grid->GetPointData()->SetScalars(values);
  const auto t1 = clock::now();
  vtkNew<vtkFlyingEdges3D> fe;
  fe->SetInputData(grid);
  fe->SetValue(0, 0.0);
  fe->ComputeNormalsOff();
  fe->ComputeGradientsOff();
  fe->Update();
  const auto t2 = clock::now();
  vtkNew<vtkMassProperties> mass;
  mass->SetInputConnection(fe->GetOutputPort());
  mass->Update();
  McResult r;
  r.volume_error = std::abs(mass->GetVolume() / s.volume() - 1);
  r.sample_s = std::chrono::duration<double>(t1 - t0).count();
  r.extract_s = std::chrono::duration<double>(t2 - t1).count();
  r.triangles = static_cast<long>(fe->GetOutput()->GetNumberOfPolys());
  return r;
}

void FlyingEdgesAtCgalVolumeError(benchmark::State& state) {
  const mesh::ShellShape s = sphere(0.03);
  const mesh::MeshOptions o;
  const auto c0 = std::chrono::steady_clock::now();
  const mesh::TriangleMesh cgal = mesh::mesh_surface(s, o);
  const double cgal_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
  const double target = std::abs(mesh::enclosed_volume(cgal) / s.volume() - 1);
  int n = 16;
  while (marching_cubes(s, n).volume_error > target && n < 1024) n += 8;
  McResult r;
  for (auto _ : state) r = marching_cubes(s, n);
  state.counters["grid_n"] = n;
  state.counters["mc_triangles"] = static_cast<double>(r.triangles);
  state.counters["mc_volume_error"] = r.volume_error;
  state.counters["mc_extract_tri_per_s"] = static_cast<double>(r.triangles) / r.extract_s;
  state.counters["mc_total_tri_per_s"] =
      static_cast<double>(r.triangles) / (r.sample_s + r.extract_s);
  state.counters["mc_total_s"] = r.sample_s + r.extract_s;
  state.counters["cgal_triangles"] = static_cast<double>(cgal.faces.size());
  state.counters["cgal_volume_error"] = target;
  state.counters["cgal_s"] = cgal_s;
  state.counters["cgal_tri_per_s"] = static_cast<double>(cgal.faces.size()) / cgal_s;
}
BENCHMARK(FlyingEdgesAtCgalVolumeError)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
