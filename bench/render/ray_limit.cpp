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
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
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
  /// fastest repetition by wall clock, and by process CPU time (each its own minimum)
  double wall_s = std::numeric_limits<double>::infinity();
  double cpu_s = std::numeric_limits<double>::infinity();
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
  best.wall_s = std::min(best.wall_s, wall);
  best.cpu_s = std::min(best.cpu_s, cpu);
}

/// Barycentric coordinates (all three) and t of `ray` against triangle `p`, in double precision
/// (Moeller & Trumbore 1997): the exact answer to within 1e-16 relative, to judge a disagreement.
std::array<double, 4> exact_hit(const Ray& r, const Primitive& p) {
  const auto d3 = [](const Vec3& v) { return std::array<double, 3>{v.x, v.y, v.z}; };
  const auto sub = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::array<double, 3>{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  };
  const auto crs = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::array<double, 3>{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                                 a[0] * b[1] - a[1] * b[0]};
  };
  const auto dt = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  };
  const auto a = d3(p.a), e1 = sub(d3(p.b), a), e2 = sub(d3(p.c), a);
  const auto o = d3(r.origin), d = d3(r.direction);
  const auto pv = crs(d, e2);
  const double det = dt(e1, pv);
  const auto tv = sub(o, a);
  const double u = dt(tv, pv) / det;
  const auto qv = crs(tv, e1);
  const double v = dt(d, qv) / det;
  return {1 - u - v, u, v, dt(e2, qv) / det};
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
  Image unrecorded;
  for (int r = 0; r < std::max(1, repetitions / 2); ++r) {
    const std::clock_t c0 = std::clock();
    const auto w0 = std::chrono::steady_clock::now();
    RenderOptions opt;
    opt.threads = threads;
    unrecorded = render(scene, opt).image;
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
    frame.wall_s = std::min(frame.wall_s, wall);
    frame.cpu_s = std::min(frame.cpu_s, double(std::clock() - c0) / CLOCKS_PER_SEC);
  }
  // 2. Its rays (one thread: the rays do not depend on the thread count, the order then does not
  // either).
  Recorder rec(scene.camera().position());
  set_ray_recorder(&rec);
  RenderOptions one;
  one.threads = 1;
  const Image recorded = render(scene, one).image;
  set_ray_recorder(nullptr);
  // The recorded frame is the frame: the hook changes no answer and the image does not depend on
  // the thread count (render/integrator/whitted.h), so every pixel must be bit-identical.
  const Image::Pixels &p0 = unrecorded.pixels(), &p1 = recorded.pixels();
  if (p0.size() != p1.size() || std::memcmp(p0.data(), p1.data(), p0.size() * sizeof(Rgb)) != 0) {
    std::fprintf(stderr, "ray_limit: the frame rendered while recording differs from the frame\n");
    return 1;
  }

  const EmbreeScene es(scene, threads);
  std::printf("ray_limit: %s, %zu triangles, %d x %d, %d spp, %d threads, best of %d\n",
              path.c_str(), st.triangles, scene.settings().width, scene.settings().height,
              scene.settings().samples_per_pixel, threads, repetitions);
  std::printf("%-10s %9s %14s %15s %12s %12s %9s %10s\n", "rays", "count", "thaw [Mray/s]",
              "Embree [Mray/s]", "thaw/Embree", "(CPU-time)", "mismatch", "self-hits");

  // Agreement bound: both compute a hit from the same float vertices; the hit point carries a
  // rounding error of a few ulps of the largest coordinate involved (watertight test: pbrt-v4
  // 6.5.3, gamma(7) of the sheared coordinates plus the shear's gamma(5)), so t differs by at most
  // 2 * gamma(16) * (max |vertex| + |origin|) / |direction| (the sum of both sides' bounds).
  float extent = 0;
  for (const Primitive& p : scene.primitives())
    for (const Vec3* c : {&p.a, &p.b, &p.c})
      extent = std::max({extent, std::fabs(c->x), std::fabs(c->y), std::fabs(c->z)});
  const float eps = std::numeric_limits<float>::epsilon() * 0.5f;
  const float g16 = 16 * eps / (1 - 16 * eps);
  // A hit one side reports and the other not is a self-hit when the ray starts on that triangle
  // within the same bound and meets it within that distance of its origin: thaw offsets its
  // secondary origins by the hit point's error bound (offset_ray_origin) and never re-hits the
  // surface it leaves; Embree, given the same origin and tnear = 0, may. Not a traversal error.
  const auto self_hit = [&](const Ray& r, std::uint32_t prim, float t) {
    const Primitive& p = scene.primitives()[prim];
    const Vec3 n = normalize(cross(p.b - p.a, p.c - p.a));
    const float bound = 2 * g16 * (extent + length(abs(r.origin)));
    return std::fabs(dot(r.origin - p.a, n)) <= bound &&
           std::fabs(t * dot(r.direction, n)) <= bound;
  };
  // A ray through a triangle's edge must hit one of the triangles sharing it (watertight test:
  // Woop, Benthin & Wald 2013, which thaw uses); a side that reports a farther hit or none there
  // passed through a crack. "At the edge": the exact barycentric coordinate of the nearer side's
  // hit is within the rounding bound above, relative to the triangle's smallest altitude.
  const auto at_edge = [&](const Ray& r, std::uint32_t prim) {
    const Primitive& p = scene.primitives()[prim];
    const auto e = exact_hit(r, p);
    const float longest = std::max({length(p.b - p.a), length(p.c - p.b), length(p.a - p.c)});
    const float altitude = length(cross(p.b - p.a, p.c - p.a)) / longest;
    const float bound = 2 * g16 * (extent + length(abs(r.origin))) / altitude;
    return std::min({std::fabs(e[0]), std::fabs(e[1]), std::fabs(e[2])}) <= bound;
  };
  const auto embree_closest = [&](const Ray& r) {
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray = to_embree(r);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(es.scene, &ctx, &rh);
    return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? Result{} : Result{rh.hit.primID, rh.ray.tfar};
  };
  const auto thaw_closest = [&](const Ray& r) {
    Hit h;
    return scene.intersect(r, h) ? Result{h.prim, h.t} : Result{};
  };

  std::size_t total_rays = 0, total_mismatch = 0, total_self = 0, cracks[2] = {0, 0};
  Timing thaw_all{0, 0}, embree_all{0, 0};
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
        timed(tt, n, threads, [&](std::size_t i) { a[i] = thaw_closest(rays[i]); });
        timed(te, n, threads, [&](std::size_t i) { b[i] = embree_closest(rays[i]); });
      }
    }
    std::size_t mismatch = 0, self = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (a[i].prim == b[i].prim) continue;
      Result ta = a[i], eb = b[i];
      if (k == kShadow) {  // which triangle the occluding side met: its closest hit
        ta = ta.prim ? thaw_closest(rays[i]) : Result{};
        eb = eb.prim ? embree_closest(rays[i]) : Result{};
      }
      const bool thaw_hit = ta.prim != Result::kMiss, embree_hit = eb.prim != Result::kMiss;
      if (thaw_hit && embree_hit) {
        const float tol =
            2 * g16 * (extent + length(abs(rays[i].origin))) / length(rays[i].direction);
        if (k == kShadow || std::fabs(ta.t - eb.t) <= tol) continue;  // a shared edge
      } else if (embree_hit && self_hit(rays[i], eb.prim, eb.t)) {
        ++self;
        continue;
      }
      // One side's hit is the nearer (or the only) one and lies on an edge: the other passed
      // through a crack there (cracks[0]: thaw did, cracks[1]: Embree did).
      const bool thaw_nearer = thaw_hit && (!embree_hit || ta.t < eb.t);
      const Result& nearer = thaw_nearer ? ta : eb;
      if (k != kShadow && nearer.prim != Result::kMiss && at_edge(rays[i], nearer.prim)) {
        ++cracks[thaw_nearer ? 1 : 0];
        continue;
      }
      if (mismatch < 5) {
        std::fprintf(stderr, "  %s ray %zu: thaw prim %u t %.9g, Embree prim %u t %.9g\n",
                     kKindName[k], i, ta.prim, double(ta.t), eb.prim, double(eb.t));
        for (const Result& x : {ta, eb})
          if (x.prim != Result::kMiss) {
            const auto e = exact_hit(rays[i], scene.primitives()[x.prim]);
            std::fprintf(stderr, "    prim %u exact: b = %.3g %.3g %.3g, t = %.9g\n", x.prim, e[0],
                         e[1], e[2], e[3]);
          }
      }
      ++mismatch;
    }
    std::printf("%-10s %9zu %14.2f %15.2f %12.3f %12.3f %9zu %10zu\n", kKindName[k], n,
                double(n) / tt.wall_s * 1e-6, double(n) / te.wall_s * 1e-6, te.wall_s / tt.wall_s,
                te.cpu_s / tt.cpu_s, mismatch, self);
    total_rays += n;
    total_mismatch += mismatch;
    total_self += self;
    thaw_all.wall_s += tt.wall_s;
    thaw_all.cpu_s += tt.cpu_s;
    embree_all.wall_s += te.wall_s;
    embree_all.cpu_s += te.cpu_s;
  }
  std::printf("%-10s %9zu %14.2f %15.2f %12.3f %12.3f %9zu %10zu\n", "all", total_rays,
              double(total_rays) / thaw_all.wall_s * 1e-6,
              double(total_rays) / embree_all.wall_s * 1e-6, embree_all.wall_s / thaw_all.wall_s,
              embree_all.cpu_s / thaw_all.cpu_s, total_mismatch, total_self);
  const double frame_per_cpu = double(total_rays) / frame.cpu_s * 1e-6;
  const double embree_per_cpu = double(total_rays) / embree_all.cpu_s * 1e-6;
  std::printf(
      "frame: %.3f s wall, %.3f CPU-s, %.2f Mrays per CPU-second = %.3f of Embree's replay of the "
      "same rays (%.2f Mrays per CPU-second); thaw's traversal alone is %.0f %% of the frame's "
      "CPU time (the rest: camera sampling, shading, film)\n",
      frame.wall_s, frame.cpu_s, frame_per_cpu, frame_per_cpu / embree_per_cpu, embree_per_cpu,
      100.0 * thaw_all.cpu_s / frame.cpu_s);
  if (total_self > 0)
    std::printf(
        "self-hits: %zu rays Embree found re-hitting the triangle they start on, at t "
        "within rounding (thaw's offset origins exclude these); not counted as mismatches\n",
        total_self);
  std::printf(
      "cracks: %zu rays passed between two triangles at their shared edge in thaw, %zu in "
      "Embree (the other found the hit on that edge); not counted as mismatches\n",
      cracks[0], cracks[1]);
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
