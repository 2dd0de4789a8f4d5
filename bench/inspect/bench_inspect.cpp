// Cost of `thaw inspect` per surface: reading an OBJ strictly (thaw) vs vtkOBJReader (the peer
// users know, which validates nothing), the whole inspection (edges, orientation, duplicates,
// vtkFeatureEdges x2, vtkMassProperties, vtkMeshQuality x3) and the .vtp export. The surface is
// an icosphere (20 * 4^L triangles) written at 17 significant digits like thaw's meshes.
#include <benchmark/benchmark.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPolyData.h>

#include <unistd.h>
#include <filesystem>

#include "base/obj_reader.h"
#include "base/obj_writer.h"
#include "src/inspect/mesh_report.h"
#include "src/inspect/pvd_writer.h"
#include "tests/src/inspect/icosphere.h"

namespace {
using thaw::inspect::TriangleMesh;
namespace fs = std::filesystem;

/// A 81920-triangle sphere OBJ in a temporary folder (created once).
const fs::path& sphere_obj() {
  static const fs::path path = [] {
    const fs::path dir =
        fs::temp_directory_path() / ("thaw-bench-inspect-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path p = dir / "sphere.obj";
    thaw::meshio::write_obj(p, thaw::inspect::testing::icosphere(0.015, 6));
    return p;
  }();
  return path;
}

void BM_ReadObjStrict(benchmark::State& state) {
  std::int64_t triangles = 0;
  for (auto _ : state) {
    const TriangleMesh m = thaw::meshio::read_obj(sphere_obj());
    triangles = static_cast<std::int64_t>(m.triangles.size());
    benchmark::DoNotOptimize(m.vertices.data());
  }
  state.counters["triangles_per_s"] = benchmark::Counter(
      static_cast<double>(triangles), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ReadObjStrict)->Unit(benchmark::kMillisecond);

void BM_ReadObjVtk(benchmark::State& state) {
  std::int64_t triangles = 0;
  for (auto _ : state) {
    vtkNew<vtkOBJReader> reader;
    reader->SetFileName(sphere_obj().c_str());
    reader->Update();
    triangles = reader->GetOutput()->GetNumberOfPolys();
  }
  state.counters["triangles_per_s"] = benchmark::Counter(
      static_cast<double>(triangles), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ReadObjVtk)->Unit(benchmark::kMillisecond);

void BM_InspectMesh(benchmark::State& state) {
  const TriangleMesh m = thaw::meshio::read_obj(sphere_obj());
  for (auto _ : state) benchmark::DoNotOptimize(thaw::inspect::inspect_mesh(m, "sphere").volume_m3);
  state.counters["triangles_per_s"] = benchmark::Counter(
      static_cast<double>(m.triangles.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_InspectMesh)->Unit(benchmark::kMillisecond);

void BM_InspectObj(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(thaw::inspect::inspect_obj(sphere_obj()).volume_m3);
}
BENCHMARK(BM_InspectObj)->Unit(benchmark::kMillisecond);

void BM_WriteVtp(benchmark::State& state) {
  const TriangleMesh m = thaw::meshio::read_obj(sphere_obj());
  const fs::path out = sphere_obj().parent_path() / "sphere.vtp";
  for (auto _ : state) thaw::inspect::write_vtp(out, m);
}
BENCHMARK(BM_WriteVtp)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::error_code ec;
  fs::remove_all(sphere_obj().parent_path(), ec);
  return 0;
}
