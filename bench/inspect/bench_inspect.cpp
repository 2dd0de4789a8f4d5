// Cost of `thaw inspect` per surface: reading an OBJ strictly (thaw) vs vtkOBJReader (the peer
// users know, which validates nothing), the whole inspection (edges, orientation, duplicates,
// vtkFeatureEdges x2, vtkMassProperties, vtkMeshQuality x3) and the .vtp export. The surface is
// an icosphere (20 * 4^L triangles) written at 17 significant digits like thaw's meshes.
#include <benchmark/benchmark.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPolyData.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <unistd.h>

#include "src/inspect/mesh_report.h"
#include "src/inspect/obj_reader.h"
#include "src/inspect/pvd_writer.h"

namespace {
using thaw::inspect::TriangleMesh;
namespace fs = std::filesystem;

TriangleMesh icosphere(int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<std::array<double, 3>> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                          {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                          {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<std::int64_t, 3>> f = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  auto unit = [](std::array<double, 3> p) {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return std::array<double, 3>{0.015 * p[0] / n, 0.015 * p[1] / n, 0.015 * p[2] / n};
  };
  for (auto& p : v) p = unit(p);
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::int64_t, std::int64_t>, std::int64_t> mid;
    auto midpoint = [&](std::int64_t a, std::int64_t b) {
      const auto key = std::minmax(a, b);
      if (auto it = mid.find(key); it != mid.end()) return it->second;
      v.push_back(unit({v[a][0] + v[b][0], v[a][1] + v[b][1], v[a][2] + v[b][2]}));
      return mid[key] = static_cast<std::int64_t>(v.size() - 1);
    };
    std::vector<std::array<std::int64_t, 3>> next;
    for (const auto& tri : f) {
      const auto a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]), c = midpoint(tri[2], tri[0]);
      next.insert(next.end(), {{tri[0], a, c}, {tri[1], b, a}, {tri[2], c, b}, {a, b, c}});
    }
    f = std::move(next);
  }
  return {v, f};
}

/// A 81920-triangle sphere OBJ in a temporary folder (created once).
const fs::path& sphere_obj() {
  static const fs::path path = [] {
    const fs::path dir = fs::temp_directory_path() / ("thaw-bench-inspect-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path p = dir / "sphere.obj";
    thaw::inspect::write_obj(p, icosphere(6));
    return p;
  }();
  return path;
}

void BM_ReadObjStrict(benchmark::State& state) {
  std::int64_t triangles = 0;
  for (auto _ : state) {
    const TriangleMesh m = thaw::inspect::read_obj(sphere_obj());
    triangles = static_cast<std::int64_t>(m.triangles.size());
    benchmark::DoNotOptimize(m.vertices.data());
  }
  state.counters["triangles_per_s"] =
      benchmark::Counter(static_cast<double>(triangles), benchmark::Counter::kIsIterationInvariantRate);
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
  state.counters["triangles_per_s"] =
      benchmark::Counter(static_cast<double>(triangles), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ReadObjVtk)->Unit(benchmark::kMillisecond);

void BM_InspectMesh(benchmark::State& state) {
  const TriangleMesh m = thaw::inspect::read_obj(sphere_obj());
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
  const TriangleMesh m = thaw::inspect::read_obj(sphere_obj());
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
