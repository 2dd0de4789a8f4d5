// How close thaw's BVH is to what this machine can do (issue 30, item 1): records the rays of one
// real frame (render/accel/ray_record.h: every Scene::intersect and Scene::occluded query of a
// Whitted frame), sorted into camera rays (closest-hit rays from the camera position), secondary
// rays (the other closest-hit rays: reflection and refraction) and shadow rays (any-hit), then
// replays the same rays on the same triangles through thaw's Scene::intersect / Scene::occluded
// and through Intel Embree 3's rtcIntersect1 / rtcOccluded1, same OpenMP threads, same run,
// interleaved, best of several repetitions. Prints rays per second per kind and thaw / Embree, the
// frame's own rays per CPU-second as a fraction of Embree's replay, and checks that both agree on
// every ray (hit or miss; the same triangle or the same t within the bound below); a disagreement
// is a bug in one of them, so the program exits 1 when any ray disagrees.
// Usage: ray_limit [scene.toml] [threads] [repetitions]; only triangle scenes (Embree is given
// the same triangles; spheres, boxes and planes would need user geometry).
#include <embree3/rtcore.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include "render/accel/ray_record.h"
#include "render/format/scene_parser.h"
#include "render/integrator/whitted.h"
#include "render/scene/scene.h"

namespace thaw::render {
namespace {

enum Kind { kCamera, kSecondary, kShadow, kKinds };
const char* const kKindName[kKinds] = {"camera", "secondary", "shadow"};

/// Sorts the recorded rays by kind (the frame is recorded on one thread: the order is the
/// frame's own; the mutex only guards against a caller that records with more).
class Recorder final : public RayRecorder {
 public:
  explicit Recorder(const Vec3& camera) : m_camera(camera) {}
  void record(RayQuery query, const Ray& ray) noexcept override {
    const std::lock_guard<std::mutex> lock(m_mutex);
    if (query == RayQuery::any)
      rays[kShadow].push_back(ray);
    else if (ray.origin == m_camera)
      rays[kCamera].push_back(ray);
    else
      rays[kSecondary].push_back(ray);
  }
  std::vector<Ray> rays[kKinds];

 private:
  Vec3 m_camera;
  std::mutex m_mutex;
};

struct EmbreeScene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  EmbreeScene(const Scene& s, int threads) {
    const std::string config = "threads=" + std::to_string(threads);
    device = rtcNewDevice(config.c_str());
    scene = rtcNewScene(device);
    // One geometry whose primitive i is thaw's primitive i (leaf order): hits compare by index.
    // Default build quality (RTC_BUILD_QUALITY_MEDIUM), as an application would use it.
    const std::vector<Primitive>& prims = s.primitives();
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * prims.size()));
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), prims.size()));
    for (std::size_t i = 0; i < prims.size(); ++i) {
      const Vec3* corner[3] = {&prims[i].a, &prims[i].b, &prims[i].c};
      for (int k = 0; k < 3; ++k) {
        v[9 * i + 3 * k] = corner[k]->x;
        v[9 * i + 3 * k + 1] = corner[k]->y;
        v[9 * i + 3 * k + 2] = corner[k]->z;
        idx[3 * i + k] = static_cast<unsigned>(3 * i + k);
      }
    }
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene);
  }
  ~EmbreeScene() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
};

RTCRay to_embree(const Ray& r) {
  RTCRay e;
  e.org_x = r.origin.x;
  e.org_y = r.origin.y;
  e.org_z = r.origin.z;
  e.dir_x = r.direction.x;
  e.dir_y = r.direction.y;
  e.dir_z = r.direction.z;
  e.tnear = 0.0f;
  e.tfar = r.t_max;
  e.mask = ~0u;
  e.flags = 0;
  e.time = 0.0f;
  e.id = 0;
  return e;
}

/// Result of one ray: the hit primitive (kMiss if none) and its distance.
struct Result {
  static constexpr std::uint32_t kMiss = 0xffffffffu;
  std::uint32_t prim = kMiss;
  float t = 0;
};

struct Timing {
  double wall_s = std::numeric_limits<double>::infinity();
  double cpu_s = 0;
};

/// Runs `f(i)` for every ray on `threads` OpenMP threads; keeps the fastest of the repetitions.
template <class F>
void timed(Timing& best, std::size_t n, int threads, F&& f) {
  const std::clock_t c0 = std::clock();
  const auto w0 = std::chrono::steady_clock::now();
#pragma omp parallel for num_threads(threads) schedule(dynamic, 4096)
  for (std::size_t i = 0; i < n; ++i) f(i);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
  if (wall < best.wall_s) best = {wall, cpu};
}

int run(int argc, char** argv) {
  const std::string path =
      argc > 1 ? argv[1] : std::string(THAW_SOURCE_DIR) + "/data/scenes/s1_ice_shell_mesh.toml";
  const int threads = argc > 2 ? std::atoi(argv[2]) : 2;
  const int repetitions = argc > 3 ? std::atoi(argv[3]) : 5;
  const Scene scene = build_scene(parse_scene_file(path));
  const SceneStatistics& st = scene.statistics();
  if (st.spheres + st.boxes + st.planes > 0 || st.triangles == 0) {
    std::fprintf(stderr, "ray_limit: %s has spheres, boxes or planes; only triangles compare\n",
                 path.c_str());
    return 2;
  }

  // 1. The frame, as thaw renders it (threads as given, recorder off): wall and CPU time.
  Timing frame;
  for (int r = 0; r < std::max(1, repetitions / 2); ++r) {
    const std::clock_t c0 = std::clock();
    const auto w0 = std::chrono::steady_clock::now();
    RenderOptions opt;
    opt.threads = threads;
    (void)render(scene, opt);
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
    if (wall < frame.wall_s) frame = {wall, double(std::clock() - c0) / CLOCKS_PER_SEC};
  }
  // 2. Its rays (one thread: the rays do not depend on the thread count, the order then does not
  // either).
  Recorder rec(scene.camera().position());
  set_ray_recorder(&rec);
  {
    RenderOptions opt;
    opt.threads = 1;
    (void)render(scene, opt);
  }
  set_ray_recorder(nullptr);

  const EmbreeScene es(scene, threads);
  std::printf("ray_limit: %s, %zu triangles, %d x %d, %d spp, %d threads, best of %d\n",
              path.c_str(), st.triangles, scene.settings().width, scene.settings().height,
              scene.settings().samples_per_pixel, threads, repetitions);
  std::printf("%-10s %10s %14s %14s %12s %10s\n", "rays", "count", "thaw [Mray/s]",
              "Embree [Mray/s]", "thaw/Embree", "mismatch");

  // Agreement bound on t: both compute the hit from the same float vertices; each t carries a
  // rounding error of a few ulps of the largest coordinate involved (watertight test: pbrt-v4
  // 6.5.3, delta_t <= gamma(7) * (max |vertex| + |origin|) / |direction| plus the shear's
  // gamma(5)). 2 * gamma(16) covers the sum of both sides' bounds.
  float extent = 0;
  for (const Primitive& p : scene.primitives())
    for (const Vec3* c : {&p.a, &p.b, &p.c})
      extent = std::max({extent, std::fabs(c->x), std::fabs(c->y), std::fabs(c->z)});
  const float g16 = 16 * std::numeric_limits<float>::epsilon() * 0.5f /
                    (1 - 16 * std::numeric_limits<float>::epsilon() * 0.5f);

  std::size_t total_rays = 0, total_mismatch = 0;
  double thaw_all_s = 0, embree_all_s = 0, embree_all_cpu = 0;
  for (int k = 0; k < kKinds; ++k) {
    const std::vector<Ray>& rays = rec.rays[k];
    const std::size_t n = rays.size();
    std::vector<Result> a(n), b(n);
    Timing tt, te;
    for (int r = 0; r < repetitions; ++r) {  // interleaved: both see the same load
      if (k == kShadow) {
        timed(tt, n, threads, [&](std::size_t i) { a[i].prim = scene.occluded(rays[i]) ? 1 : 0; });
        timed(te, n, threads, [&](std::size_t i) {
          RTCIntersectContext ctx;
          rtcInitIntersectContext(&ctx);
          RTCRay e = to_embree(rays[i]);
          rtcOccluded1(es.scene, &ctx, &e);
          b[i].prim = e.tfar < 0.0f ? 1 : 0;  // rtcOccluded1 sets tfar = -inf on a hit
        });
      } else {
        timed(tt, n, threads, [&](std::size_t i) {
          Hit h;
          a[i] = scene.intersect(rays[i], h) ? Result{h.prim, h.t} : Result{};
        });
        timed(te, n, threads, [&](std::size_t i) {
          RTCIntersectContext ctx;
          rtcInitIntersectContext(&ctx);
          RTCRayHit rh;
          rh.ray = to_embree(rays[i]);
          rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          rtcIntersect1(es.scene, &ctx, &rh);
          b[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? Result{}
                                                          : Result{rh.hit.primID, rh.ray.tfar};
        });
      }
    }
    std::size_t mismatch = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (a[i].prim == b[i].prim) continue;
      const bool both_hit = a[i].prim != Result::kMiss && b[i].prim != Result::kMiss;
      const float tol =
          2 * g16 * (extent + length(abs(rays[i].origin))) / length(rays[i].direction);
      if (k != kShadow && both_hit && std::fabs(a[i].t - b[i].t) <= tol) continue;  // shared edge
      if (mismatch < 5)
        std::fprintf(stderr, "  %s ray %zu: thaw prim %u t %.9g, Embree prim %u t %.9g\n",
                     kKindName[k], i, a[i].prim, double(a[i].t), b[i].prim, double(b[i].t));
      ++mismatch;
    }
    const double mt = double(n) / tt.wall_s * 1e-6, me = double(n) / te.wall_s * 1e-6;
    std::printf("%-10s %10zu %14.2f %14.2f %12.3f %10zu\n", kKindName[k], n, mt, me, mt / me,
                mismatch);
    total_rays += n;
    total_mismatch += mismatch;
    thaw_all_s += tt.wall_s;
    embree_all_s += te.wall_s;
    embree_all_cpu += te.cpu_s;
  }
  const double mt = double(total_rays) / thaw_all_s * 1e-6;
  const double me = double(total_rays) / embree_all_s * 1e-6;
  std::printf("%-10s %10zu %14.2f %14.2f %12.3f %10zu\n", "all", total_rays, mt, me, mt / me,
              total_mismatch);
  const double frame_per_cpu = double(total_rays) / frame.cpu_s * 1e-6;
  const double embree_per_cpu = double(total_rays) / embree_all_cpu * 1e-6;
  std::printf(
      "frame: %.3f s wall, %.3f CPU-s, %.2f Mrays per CPU-second = %.3f of Embree's replay of "
      "the same rays (%.2f Mrays per CPU-second)\n",
      frame.wall_s, frame.cpu_s, frame_per_cpu, frame_per_cpu / embree_per_cpu, embree_per_cpu);
  if (total_mismatch > 0) {
    std::fprintf(stderr, "ray_limit: thaw and Embree disagree on %zu of %zu rays\n", total_mismatch,
                 total_rays);
    return 1;
  }
  return 0;
}

}  // namespace
}  // namespace thaw::render

int main(int argc, char** argv) {
  return thaw::render::run(argc, argv);
}
