// BVH throughput of thaw's Scene::intersect against Intel Embree 3's rtcIntersect1 (the single-ray
// API), single thread, on the same mesh (the S1 ice shell: two icospheres of 20480 triangles) and
// the same rays: 10^6 primary rays of the S1 camera (1000x1000) and 10^6 random rays (origins in
// the mesh's bounding box enlarged 1.5x, directions uniform on the sphere). Rays per second are
// reported as the counter `rays_per_s`; docs/benchmarks.md has the ratios.
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>

#include <cmath>
#include <random>

#include "render/format/scene_parser.h"
#include "render/geometry/obj_loader.h"
#include "render/scene/scene.h"

namespace thaw::render {
namespace {

struct Fixture {
  TriangleMesh outer, inner;
  Scene scene;
  std::vector<Ray> primary, random;

  Fixture() {
    const std::string dir = std::string(THAW_SOURCE_DIR) + "/data/scenes/";
    outer = load_obj(dir + "meshes/sphere_r1.0.obj");
    inner = load_obj(dir + "meshes/sphere_r0.7.obj");
    SceneDescription d = parse_scene_file(dir + "s1_ice_shell_mesh.toml");
    d.objects.pop_back();  // the floor: only the shell is compared
    d.image.width = d.image.height = 1000;
    scene = build_scene(d);
    for (int y = 0; y < 1000; ++y)
      for (int x = 0; x < 1000; ++x) primary.push_back(scene.camera().generate(x + 0.5f, y + 0.5f));
    std::mt19937 rng(12345);
    std::uniform_real_distribution<float> u(-1.5f, 1.5f), n(-1.0f, 1.0f);
    while (random.size() < 1000000) {
      const Vec3 d3{n(rng), n(rng), n(rng)};
      const float l = length(d3);
      if (l > 1.0f || l < 1e-3f) continue;  // rejection: uniform directions
      random.push_back(Ray{{u(rng), u(rng), u(rng)}, d3 / l});
    }
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

void thaw_intersect(benchmark::State& state, const std::vector<Ray>& rays) {
  const Scene& s = fixture().scene;
  std::size_t hits = 0;
  for (auto _ : state) {
    for (const Ray& r : rays) {
      Hit h;
      hits += s.intersect(r, h);
    }
  }
  benchmark::DoNotOptimize(hits);
  state.counters["rays_per_s"] =
      benchmark::Counter(double(rays.size()), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["hit_fraction"] = double(hits) / double(state.iterations() * rays.size());
}

struct EmbreeScene {
  RTCDevice device;
  RTCScene scene;
  EmbreeScene() {
    device = rtcNewDevice("threads=1");
    scene = rtcNewScene(device);
    // Default build quality (RTC_BUILD_QUALITY_MEDIUM), as an application would use it.
    for (const TriangleMesh* m : {&fixture().outer, &fixture().inner}) {
      RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m->positions.size()));
      for (std::size_t i = 0; i < m->positions.size(); ++i) {
        v[3 * i] = m->positions[i].x;
        v[3 * i + 1] = m->positions[i].y;
        v[3 * i + 2] = m->positions[i].z;
      }
      auto* idx = static_cast<unsigned*>(
          rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                  3 * sizeof(unsigned), m->triangles.size()));
      for (std::size_t t = 0; t < m->triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) idx[3 * t + k] = m->triangles[t][k];
      rtcCommitGeometry(g);
      rtcAttachGeometry(scene, g);
      rtcReleaseGeometry(g);
    }
    rtcCommitScene(scene);
  }
  ~EmbreeScene() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
};

void embree_intersect(benchmark::State& state, const std::vector<Ray>& rays) {
  static EmbreeScene es;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  std::size_t hits = 0;
  for (auto _ : state) {
    for (const Ray& r : rays) {
      RTCRayHit rh;
      rh.ray.org_x = r.origin.x;
      rh.ray.org_y = r.origin.y;
      rh.ray.org_z = r.origin.z;
      rh.ray.dir_x = r.direction.x;
      rh.ray.dir_y = r.direction.y;
      rh.ray.dir_z = r.direction.z;
      rh.ray.tnear = 0.0f;
      rh.ray.tfar = r.t_max;
      rh.ray.mask = ~0u;
      rh.ray.flags = 0;
      rh.ray.time = 0.0f;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(es.scene, &ctx, &rh);
      hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
  }
  benchmark::DoNotOptimize(hits);
  state.counters["rays_per_s"] =
      benchmark::Counter(double(rays.size()), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["hit_fraction"] = double(hits) / double(state.iterations() * rays.size());
}

void BM_Thaw_Primary(benchmark::State& s) {
  thaw_intersect(s, fixture().primary);
}
void BM_Embree_Primary(benchmark::State& s) {
  embree_intersect(s, fixture().primary);
}
void BM_Thaw_Random(benchmark::State& s) {
  thaw_intersect(s, fixture().random);
}
void BM_Embree_Random(benchmark::State& s) {
  embree_intersect(s, fixture().random);
}

void BM_Thaw_BuildScene(benchmark::State& state) {
  const std::string dir = std::string(THAW_SOURCE_DIR) + "/data/scenes/";
  const SceneDescription d = parse_scene_file(dir + "s1_ice_shell_mesh.toml");
  for (auto _ : state) benchmark::DoNotOptimize(build_scene(d));
}

BENCHMARK(BM_Thaw_Primary)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_Embree_Primary)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_Thaw_Random)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_Embree_Random)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_Thaw_BuildScene)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace thaw::render

BENCHMARK_MAIN();
