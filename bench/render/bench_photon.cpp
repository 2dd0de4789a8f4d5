// The photon pass of render/photon/caustic_map.h on S1 (the ice shell over its floor, caustics
// on, the light made inverse-square), analytic spheres and the 2 x 20480-triangle mesh variant,
// (also with an analytic plane floor, as the default film has) at the automatic photon count
// (250k) on 1 and 2 threads: wall time per pass and photons/s.
// BM_PhotonNoise measures the relative RMS photon noise of the caustic irradiance on the floor:
// the estimate at N photons against the same estimate (same radius) from 16 N photons, over the
// floor points where the caustic is brighter than 10 % of its peak, so the kernel's bias (the
// same in both) cancels and only the sampling error remains. Figures: docs/benchmarks.md.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include "render/format/scene_parser.h"
#include "render/photon/caustic_map.h"
#include "render/scene/scene.h"

namespace thaw::render {
namespace {

Scene s1(const std::string& file, long long photons, double radius = 0) {
  const bool plane_floor = file.ends_with("+plane");
  SceneDescription d = parse_scene_file(std::string(THAW_SOURCE_DIR) + "/data/scenes/" +
                                        (plane_floor ? file.substr(0, file.size() - 6) : file));
  if (plane_floor) {  // the default film's floor: an analytic plane instead of two huge triangles
    ObjectDescription& floor = d.objects.back();
    floor.shape = ObjectDescription::Shape::plane;
    floor.point = {0.0, -1.0, 0.0};
    floor.normal = {0.0, 1.0, 0.0};
  }
  d.caustics.enabled = true;
  d.caustics.photons = photons;
  if (radius > 0) d.caustics.radius = radius;
  for (auto& l : d.lights) {
    l.falloff = LightDescription::Falloff::inverse_square;
    l.intensity = 80.0;  // about the old brightness at the shell (distance 8.2)
  }
  return build_scene(d);
}

void BM_PhotonPass(benchmark::State& state, const std::string& file) {
  const Scene scene = s1(file, photon::kDefaultPhotons);
  const int threads = static_cast<int>(state.range(0));
  std::size_t stored = 0;
  double rays = 0;
  for (auto _ : state) {
    const photon::CausticMap map = photon::CausticMap::build(scene, threads);
    stored = map.statistics().photons_stored;
    rays = double(map.statistics().rays);
    benchmark::DoNotOptimize(stored);
  }
  state.counters["rays_per_photon"] = rays / double(photon::kDefaultPhotons);
  state.counters["photons_per_s"] = benchmark::Counter(
      double(photon::kDefaultPhotons), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["stored"] = double(stored);
}
BENCHMARK_CAPTURE(BM_PhotonPass, s1_analytic, std::string("s1_ice_shell.toml"))
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_PhotonPass, s1_mesh, std::string("s1_ice_shell_mesh.toml"))
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_PhotonPass, s1_mesh_plane_floor, std::string("s1_ice_shell_mesh.toml+plane"))
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_PhotonNoise(benchmark::State& state) {
  const long long n = state.range(0);
  const Scene coarse = s1("s1_ice_shell.toml", n);
  const photon::CausticMap estimate = photon::CausticMap::build(coarse, 2);
  const double radius = estimate.statistics().targets.at(0).radius;
  const photon::CausticMap reference =
      photon::CausticMap::build(s1("s1_ice_shell.toml", 16 * n, radius), 2);
  double sum2 = 0, ref2 = 0, peak = 0;
  int points = 0;
  for (auto _ : state) {
    // The floor (y = -1) under and beside the shell, on a grid of 2 mm (R = 1 m in S1 units).
    std::vector<std::pair<float, float>> lit;
    for (int pass = 0; pass < 2; ++pass)
      for (int i = -500; i <= 1500; ++i)
        for (int k = -1500; k <= 500; k += 4) {
          const Vec3 p{0.002f * float(i), -1.0f, 0.002f * float(k)};
          const float r = reference.irradiance(p, {0, 1, 0}).g;
          if (pass == 0) {
            peak = std::max(peak, double(r));
          } else if (r > 0.1 * peak) {
            const float e = estimate.irradiance(p, {0, 1, 0}).g;
            sum2 += double(e - r) * double(e - r);
            ref2 += double(r) * double(r);
            ++points;
          }
        }
  }
  state.counters["relative_rms_noise"] = std::sqrt(sum2 / ref2);
  state.counters["points"] = points;
  state.counters["radius"] = radius;
}
BENCHMARK(BM_PhotonNoise)->Arg(62500)->Arg(250000)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace thaw::render

BENCHMARK_MAIN();
