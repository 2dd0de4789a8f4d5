// How close thaw's BVH is to what this machine can do (issue 30, item 1): records the rays of one
// real frame (render/accel/ray_record.h: every Scene::intersect and Scene::occluded query of a
// Whitted frame and of its caustic photon pass), sorted into camera rays (closest-hit rays from
// the camera position), secondary rays (the frame's other closest-hit rays: reflection and
// refraction), shadow rays (any-hit) and photon rays (the photon pass's), then replays the same
// rays on the same primitives through thaw's Scene::intersect / Scene::occluded and through Intel
// Embree 3's rtcIntersect1 / rtcOccluded1, same OpenMP threads, same run, interleaved, best of
// several repetitions. Prints rays per second per kind and thaw / Embree, the frame's own rays per
// CPU-second as a fraction of Embree's replay, where the frame's CPU time goes outside traversal,
// and checks that both agree on every ray (hit or miss; the same primitive or the same t within
// the bound below); a disagreement is a bug in one of them, so the program exits 1 when any ray
// disagrees.
//
// Embree is given thaw's triangles as its own triangles (its kernels, its watertightness) and
// thaw's spheres and boxes as user geometry whose intersection callbacks are thaw's exact tests
// (render/geometry/sphere.h, box.h): Embree's BVH and traversal, the same answers per primitive.
// Infinite planes have no bounds to put in a BVH; thaw tests them before its traversal and the
// Embree side does the same with the same code, handing the plane's distance on as tfar.
// Objects that shadow rays see through (index-matched dielectrics) are left out of a second
// Embree scene that serves the shadow rays, as thaw's occluded() skips them.
// The same rays also go through Embree's stream API (rtcIntersect1M / rtcOccluded1M, camera rays
// flagged coherent, so Embree may trace them as packets) and, where there are spheres, through
// Embree's own sphere primitives; those two are timed and their answers counted, not judged.
//
// Usage: ray_limit [scene.toml | RUN_DIR] [threads] [repetitions] [frame] [frames-only]
//   scene.toml: a `thaw render` scene (default: data/scenes/s1_ice_shell_mesh.toml);
//   RUN_DIR: a `thaw run --out RUN_DIR` folder whose simulate and mesh stages are done; its frame
//   `frame` (default 30) is built as the render stage builds it (without the caption).
#include <embree3/rtcore.h>
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include "render/accel/ray_record.h"
#include "render/format/scene_parser.h"
#include "render/geometry/box.h"
#include "render/geometry/obj_loader.h"
#include "render/geometry/plane.h"
#include "render/geometry/sphere.h"
#include "render/geometry/triangle.h"
#include "render/image/image_io.h"
#include "render/integrator/whitted.h"
#include "render/photon/caustic_map.h"
#include "render/scene/scene.h"
#include "sim/format/interface_history.h"
#include "src/mesh/mesh_series.h"
#include "src/pipeline/frame_camera.h"
#include "src/pipeline/frame_scene.h"
#include "src/pipeline/run_scenario.h"
#include "src/pipeline/water_budget.h"

namespace thaw::render {
namespace {
namespace fs = std::filesystem;

enum Kind { kCamera, kSecondary, kShadow, kPhoton, kPhotonShadow, kKinds };
const char* const kKindName[kKinds] = {"camera", "secondary", "shadow", "photon", "photon-any"};
bool any_hit(int kind) {
  return kind == kShadow || kind == kPhotonShadow;
}

/// Sorts the recorded rays by kind (the frame is recorded on one thread: the order is the
/// frame's own; the mutex only guards against a caller that records with more).
class Recorder final : public RayRecorder {
 public:
  explicit Recorder(const Vec3& camera) : m_camera(camera) {}
  void record(RayQuery query, const Ray& ray) noexcept override {
    const std::lock_guard<std::mutex> lock(m_mutex);
    if (m_stream == RayStream::photon)
      rays[query == RayQuery::any ? kPhotonShadow : kPhoton].push_back(ray);
    else if (query == RayQuery::any)
      rays[kShadow].push_back(ray);
    else if (ray.origin == m_camera)
      rays[kCamera].push_back(ray);
    else
      rays[kSecondary].push_back(ray);
  }
  void stream(RayStream s) noexcept override {
    const std::lock_guard<std::mutex> lock(m_mutex);
    m_stream = s;
  }
  std::vector<Ray> rays[kKinds];

 private:
  Vec3 m_camera;
  RayStream m_stream = RayStream::frame;
  std::mutex m_mutex;
};

/// thaw's spheres and boxes as one Embree user geometry: primitive i is thaw's primitive
/// index[i]; bounds and intersections are thaw's own.
struct UserPrimitives {
  const Primitive* prims = nullptr;
  std::vector<std::uint32_t> index;
};

Ray thaw_ray(float ox, float oy, float oz, float dx, float dy, float dz) {
  Ray r;
  r.origin = Vec3(ox, oy, oz);
  r.direction = Vec3(dx, dy, dz);
  return r;
}

/// Nearest t in (0, t_max) on thaw's primitive `p` (a sphere or a box), as Scene::intersect.
bool intersect_user(const Primitive& p, const Ray& r, float t_max, float& t) {
  if (p.kind == PrimitiveKind::sphere) return intersect_sphere(r, p.a, p.b.x, t_max, t);
  int axis;
  bool high;
  return intersect_box(r, p.a, p.b, t_max, t, axis, high);
}

void user_bounds(const RTCBoundsFunctionArguments* args) {
  const auto* u = static_cast<const UserPrimitives*>(args->geometryUserPtr);
  const Primitive& p = u->prims[u->index[args->primID]];
  Vec3 lo = p.a, hi = p.b;
  if (p.kind == PrimitiveKind::sphere) {  // centre -+ radius, one ulp outward against rounding
    const float inf = std::numeric_limits<float>::infinity();
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::nextafter(p.a[i] - p.b.x, -inf);
      hi[i] = std::nextafter(p.a[i] + p.b.x, inf);
    }
  }
  RTCBounds* b = args->bounds_o;
  b->lower_x = lo.x, b->lower_y = lo.y, b->lower_z = lo.z;
  b->upper_x = hi.x, b->upper_y = hi.y, b->upper_z = hi.z;
}

// rtcIntersect1 / rtcOccluded1 call these with N = 1, the stream API (rtcIntersect1M) with packets
// of N rays (structure of arrays, RTCRayN accessors), lanes not `valid` left alone.
void user_intersect(const RTCIntersectFunctionNArguments* args) {
  const auto* u = static_cast<const UserPrimitives*>(args->geometryUserPtr);
  const Primitive& p = u->prims[u->index[args->primID]];
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
  const unsigned N = args->N;
  for (unsigned i = 0; i < N; ++i) {
    if (!args->valid[i]) continue;
    float t;
    if (!intersect_user(
            p,
            thaw_ray(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i),
                     RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i)),
            RTCRayN_tfar(ray, N, i), t) ||
        t < RTCRayN_tnear(ray, N, i))
      continue;
    RTCRayN_tfar(ray, N, i) = t;
    RTCHitN_u(hit, N, i) = RTCHitN_v(hit, N, i) = 0.0f;
    RTCHitN_Ng_x(hit, N, i) = RTCHitN_Ng_y(hit, N, i) = RTCHitN_Ng_z(hit, N, i) = 0.0f;
    RTCHitN_primID(hit, N, i) = args->primID;
    RTCHitN_geomID(hit, N, i) = args->geomID;
    RTCHitN_instID(hit, N, i, 0) = args->context->instID[0];
  }
}

void user_occluded(const RTCOccludedFunctionNArguments* args) {
  const auto* u = static_cast<const UserPrimitives*>(args->geometryUserPtr);
  const Primitive& p = u->prims[u->index[args->primID]];
  RTCRayN* ray = args->ray;
  const unsigned N = args->N;
  for (unsigned i = 0; i < N; ++i) {
    if (!args->valid[i]) continue;
    float t;
    if (intersect_user(
            p,
            thaw_ray(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i),
                     RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i)),
            RTCRayN_tfar(ray, N, i), t) &&
        t >= RTCRayN_tnear(ray, N, i))
      RTCRayN_tfar(ray, N, i) = -std::numeric_limits<float>::infinity();
  }
}

/// Embree scenes of thaw's BVH primitives: geometry 0 its triangles (in leaf order), geometry 1
/// its spheres and boxes (user geometry). `closest` holds all; `any` (the shadow rays') leaves
/// out index-matched objects, as Scene::occluded does, and is `closest` when there are none.
struct EmbreeScene {
  static constexpr unsigned kTriangles = 0, kUser = 1, kSpheres = 2;
  RTCDevice device = nullptr;
  RTCScene closest = nullptr, any = nullptr;
  /// Spheres as Embree's own sphere primitives (RTC_GEOMETRY_TYPE_SPHERE_POINT: its kernels and
  /// its arithmetic, not thaw's), boxes as above; null without spheres, or with index-matched
  /// objects (one scene must serve both queries). Timed for comparison; its answers are Embree's.
  RTCScene native = nullptr;
  /// thaw's primitive of (geometry, Embree primitive) in `closest`, and of a native sphere
  std::vector<std::uint32_t> triangle_prim, sphere_prim;
  UserPrimitives user[3];

  EmbreeScene(const Scene& s, int threads) {
    const std::string config = "threads=" + std::to_string(threads);
    device = rtcNewDevice(config.c_str());
    bool matched = false;
    for (const SceneObject& o : s.objects()) matched |= o.index_matched;
    closest = make(s, false, false, user[0], &triangle_prim);
    any = matched ? make(s, true, false, user[1], nullptr) : closest;
    if (!matched && s.statistics().spheres > 0 &&
        rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_POINT_GEOMETRY_SUPPORTED))
      native = make(s, false, true, user[2], nullptr);
  }
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;
  ~EmbreeScene() {
    if (native) rtcReleaseScene(native);
    if (any != closest) rtcReleaseScene(any);
    rtcReleaseScene(closest);
    rtcReleaseDevice(device);
  }
  /// thaw's primitive index of an Embree hit in `closest`.
  std::uint32_t prim(unsigned geom, unsigned prim_id) const {
    return geom == kTriangles ? triangle_prim[prim_id] : user[0].index[prim_id];
  }
  /// The same in `native`.
  std::uint32_t native_prim(unsigned geom, unsigned prim_id) const {
    return geom == kTriangles ? triangle_prim[prim_id]
           : geom == kUser    ? user[2].index[prim_id]
                              : sphere_prim[prim_id];
  }

 private:
  RTCScene make(const Scene& s, bool skip_matched, bool native_spheres, UserPrimitives& u,
                std::vector<std::uint32_t>* triangle_index) {
    // Default build quality (RTC_BUILD_QUALITY_MEDIUM), as an application would use it.
    RTCScene scene = rtcNewScene(device);
    const std::vector<Primitive>& prims = s.primitives();
    std::vector<std::uint32_t> tri, spheres;
    u.prims = prims.data();
    for (std::uint32_t i = 0; i < prims.size(); ++i) {
      if (skip_matched && s.objects()[prims[i].object].index_matched) continue;
      const PrimitiveKind kind = prims[i].kind;
      (kind == PrimitiveKind::triangle                   ? tri
       : kind == PrimitiveKind::sphere && native_spheres ? spheres
                                                         : u.index)
          .push_back(i);
    }
    if (!spheres.empty()) {
      RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), spheres.size()));
      for (std::size_t i = 0; i < spheres.size(); ++i) {
        const Primitive& p = prims[spheres[i]];
        v[4 * i] = p.a.x, v[4 * i + 1] = p.a.y, v[4 * i + 2] = p.a.z, v[4 * i + 3] = p.b.x;
      }
      rtcCommitGeometry(g);
      rtcAttachGeometryByID(scene, g, kSpheres);
      rtcReleaseGeometry(g);
      sphere_prim = std::move(spheres);
    }
    if (!tri.empty()) {
      RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * tri.size()));
      auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), tri.size()));
      for (std::size_t i = 0; i < tri.size(); ++i) {
        const Primitive& p = prims[tri[i]];
        const Vec3* corner[3] = {&p.a, &p.b, &p.c};
        for (int k = 0; k < 3; ++k) {
          v[9 * i + 3 * k] = corner[k]->x;
          v[9 * i + 3 * k + 1] = corner[k]->y;
          v[9 * i + 3 * k + 2] = corner[k]->z;
          idx[3 * i + k] = static_cast<unsigned>(3 * i + k);
        }
      }
      rtcCommitGeometry(g);
      rtcAttachGeometryByID(scene, g, kTriangles);
      rtcReleaseGeometry(g);
    }
    if (!u.index.empty()) {
      RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
      rtcSetGeometryUserPrimitiveCount(g, static_cast<unsigned>(u.index.size()));
      rtcSetGeometryUserData(g, &u);
      rtcSetGeometryBoundsFunction(g, user_bounds, nullptr);
      rtcSetGeometryIntersectFunction(g, user_intersect);
      rtcSetGeometryOccludedFunction(g, user_occluded);
      rtcCommitGeometry(g);
      rtcAttachGeometryByID(scene, g, kUser);
      rtcReleaseGeometry(g);
    }
    rtcCommitScene(scene);
    if (triangle_index) *triangle_index = std::move(tri);
    return scene;
  }
};

RTCRay to_embree(const Ray& r, float t_max) {
  RTCRay e;
  e.org_x = r.origin.x;
  e.org_y = r.origin.y;
  e.org_z = r.origin.z;
  e.dir_x = r.direction.x;
  e.dir_y = r.direction.y;
  e.dir_z = r.direction.z;
  e.tnear = 0.0f;
  e.tfar = t_max;
  e.mask = ~0u;
  e.flags = 0;
  e.time = 0.0f;
  e.id = 0;
  return e;
}

/// Result of one ray: the hit primitive (kMiss if none; kPlaneBit | k for plane k) and its t.
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

/// Runs `f()` once and keeps its time if it is the fastest so far.
template <class F>
void timed_once(Timing& best, F&& f) {
  const std::clock_t c0 = std::clock();
  const auto w0 = std::chrono::steady_clock::now();
  f();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  best.wall_s = std::min(best.wall_s, wall);
  best.cpu_s = std::min(best.cpu_s, double(std::clock() - c0) / CLOCKS_PER_SEC);
}

/// Runs `f(i)` for every ray on `threads` OpenMP threads; keeps the fastest of the repetitions.
template <class F>
void timed(Timing& best, std::size_t n, int threads, F&& f) {
  timed_once(best, [&] {
#pragma omp parallel for num_threads(threads) schedule(dynamic, 4096)
    for (std::size_t i = 0; i < n; ++i) f(i);
  });
}

/// Runs `f(begin, end)` over chunks of `chunk` rays on `threads` OpenMP threads; keeps the fastest.
template <class F>
void timed_chunks(Timing& best, std::size_t n, std::size_t chunk, int threads, F&& f) {
  timed_once(best, [&] {
    const std::size_t chunks = (n + chunk - 1) / chunk;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 16)
    for (std::size_t c = 0; c < chunks; ++c) f(c * chunk, std::min(n, (c + 1) * chunk));
  });
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

/// Frame `frame` of the `thaw run` folder `dir` as its render stage builds it
/// (src/pipeline/stage_render.cpp: the run's camera, the step's meshes, the puddle's water).
SceneDescription run_frame_scene(const fs::path& dir, long frame) {
  const pipeline::RunScenario sc = pipeline::read_run_scenario(dir / "scenario.toml");
  const std::vector<sim::InterfaceRecord> rows =
      sim::read_interfaces_csv(dir / "sim/interfaces.csv");
  const fs::path mesh_dir = dir / "sim/mesh";
  const mesh::MeshManifest meshes = mesh::read_mesh_manifest(mesh_dir / "manifest.json");
  pipeline::RunScenario framed = sc;
  framed.scene.camera = pipeline::run_camera(sc, rows, meshes.geometry);
  const std::vector<pipeline::WaterBudget> water =
      pipeline::water_budget(rows, meshes.geometry, sc.simulation.materials.ice_density_kg_m3,
                             sc.simulation.materials.water_density_kg_m3);
  const mesh::StepRecord& step = meshes.steps.at(static_cast<std::size_t>(frame));
  pipeline::FrameShell shell;
  if (step.outer.file)
    shell.outer = std::make_shared<TriangleMesh>(load_obj(mesh_dir / *step.outer.file));
  if (step.inner.file)
    shell.inner = std::make_shared<TriangleMesh>(load_obj(mesh_dir / *step.inner.file));
  shell.outer_radius_m = step.outer_radius_m;
  return pipeline::frame_scene(framed, meshes.geometry, shell,
                               water.at(static_cast<std::size_t>(step.step)));
}

int run(int argc, char** argv) {
  const std::string path =
      argc > 1 ? argv[1] : std::string(THAW_SOURCE_DIR) + "/data/scenes/s1_ice_shell_mesh.toml";
  const int threads = argc > 2 ? std::atoi(argv[2]) : 2;
  const int repetitions = argc > 3 ? std::atoi(argv[3]) : 5;
  const long frame_index = argc > 4 ? std::atol(argv[4]) : 30;
  // frames-only: render and write the frame `repetitions` times and stop (for a profiler:
  // bench/render/frame_profile.sh), no photon pass alone, no recording, no replay.
  const bool frames_only = argc > 5 && std::string(argv[5]) == "frames-only";
  const bool run_dir = fs::is_directory(path);
  const Scene scene =
      build_scene(run_dir ? run_frame_scene(path, frame_index) : parse_scene_file(path));
  const SceneStatistics& st = scene.statistics();

  // 1. The frame, as thaw renders it (threads as given, recorder off): wall and CPU time; its
  // photon pass alone, and the PNG of it (written as the render stage writes it).
  Timing frame, photons, png;
  Image unrecorded;
  const fs::path png_path =
      fs::temp_directory_path() / ("ray_limit_" + std::to_string(::getpid()) + ".png");
  for (int r = 0; r < (frames_only ? repetitions : std::max(1, repetitions / 2)); ++r) {
    timed_once(frame, [&] {
      RenderOptions opt;
      opt.threads = threads;
      unrecorded = render(scene, opt).image;
    });
    if (!frames_only)
      timed_once(photons, [&] { photon::CausticMap::build(scene, threads, nullptr); });
    timed_once(png, [&] {
      write_png(png_path, unrecorded, scene.settings().exposure, 8, scene.settings().view);
    });
  }
  fs::remove(png_path);
  if (frames_only) {
    std::printf("ray_limit: %d frames of %s: best %.3f s wall, %.3f CPU-s; PNG %.3f CPU-s\n",
                repetitions, path.c_str(), frame.wall_s, frame.cpu_s, png.cpu_s);
    return 0;
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
  std::printf(
      "ray_limit: %s%s, %zu triangles, %zu spheres, %zu boxes, %zu planes, %d x %d, %d spp, %d "
      "threads, best of %d\n",
      path.c_str(), run_dir ? (" frame " + std::to_string(frame_index)).c_str() : "", st.triangles,
      st.spheres, st.boxes, st.planes, scene.settings().width, scene.settings().height,
      scene.settings().samples_per_pixel, threads, repetitions);
  std::printf("%-10s %9s %14s %15s %12s %12s %9s %10s\n", "rays", "count", "thaw [Mray/s]",
              "Embree [Mray/s]", "thaw/Embree", "(CPU-time)", "mismatch", "self-hits");

  // Agreement bound: both compute a hit from the same float vertices; the hit point carries a
  // rounding error of a few ulps of the largest coordinate involved (watertight test: pbrt-v4
  // 6.5.3, gamma(7) of the sheared coordinates plus the shear's gamma(5)), so t differs by at most
  // 2 * gamma(16) * (max |vertex| + |origin|) / |direction| (the sum of both sides' bounds).
  // Spheres and boxes are thaw's own tests on both sides: the same t, bit for bit.
  float extent = 0;
  for (const Primitive& p : scene.primitives()) {
    std::vector<Vec3> corners{p.a, p.b, p.c};  // triangle
    if (p.kind == PrimitiveKind::sphere)
      corners = {p.a + Vec3(p.b.x, p.b.x, p.b.x), p.a - Vec3(p.b.x, p.b.x, p.b.x)};
    else if (p.kind == PrimitiveKind::box)
      corners = {p.a, p.b};
    for (const Vec3& c : corners)
      extent = std::max({extent, std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)});
  }
  const float eps = std::numeric_limits<float>::epsilon() * 0.5f;
  const float g16 = 16 * eps / (1 - 16 * eps);
  const auto is_triangle = [&](std::uint32_t prim) {
    return !(prim & kPlaneBit) && scene.primitives()[prim].kind == PrimitiveKind::triangle;
  };
  // A hit one side reports and the other not is a self-hit when the ray starts on that triangle
  // within the same bound and meets it within that distance of its origin: thaw offsets its
  // secondary origins by the hit point's error bound (offset_ray_origin) and never re-hits the
  // surface it leaves; Embree, given the same origin and tnear = 0, may. Not a traversal error.
  const auto self_hit = [&](const Ray& r, std::uint32_t prim, float t) {
    if (!is_triangle(prim)) return false;
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
    if (!is_triangle(prim)) return false;
    const Primitive& p = scene.primitives()[prim];
    const auto e = exact_hit(r, p);
    const float longest = std::max({length(p.b - p.a), length(p.c - p.b), length(p.a - p.c)});
    const float altitude = length(cross(p.b - p.a, p.c - p.a)) / longest;
    const float bound = 2 * g16 * (extent + length(abs(r.origin))) / altitude;
    return std::min({std::fabs(e[0]), std::fabs(e[1]), std::fabs(e[2])}) <= bound;
  };
  // thaw accepts a triangle's hit only beyond the rounding bound of its t (render/geometry/
  // triangle.h; pbrt-v4), which grows with the triangle's extent: a ray that leaves a point just
  // above a large triangle (S4's 200 m floor) may meet it nearer than that bound, where Embree
  // reports the hit and thaw does not. Such a hit is thaw's bound when the same ray, started
  // `extent` further back, meets the same triangle in thaw's own test at the distance moved
  // plus Embree's t.
  const auto t_bound_rejected = [&](const Ray& r, std::uint32_t prim, float t) {
    if (!is_triangle(prim)) return false;
    const Primitive& p = scene.primitives()[prim];
    const float back = extent / length(r.direction);
    Ray moved = r;
    moved.origin = r.origin - r.direction * back;
    TriangleHit th;
    if (!intersect_triangle(ShearedRay(moved), p.a, p.b, p.c,
                            std::numeric_limits<float>::infinity(), th))
      return false;
    const float tol = 2 * g16 * (3 * extent + length(abs(r.origin))) / length(r.direction);
    return std::fabs(th.t - back - t) <= tol;
  };
  // The planes, as Scene::intersect / occluded test them before their traversal (the same code
  // on both sides): the nearest, or whether any lies on the ray.
  const std::vector<SceneObject>& objects = scene.objects();
  std::vector<std::uint32_t> planes;
  for (std::uint32_t i = 0; i < objects.size(); ++i)
    if (objects[i].shape == ObjectDescription::Shape::plane) planes.push_back(i);
  const auto nearest_plane = [&](const Ray& r, Result& res) {
    float t_max = r.t_max;
    for (std::uint32_t k = 0; k < planes.size(); ++k) {
      const SceneObject& o = objects[planes[k]];
      float t;
      if (intersect_plane(r, o.plane_point, o.plane_normal, t_max, t)) {
        t_max = t;
        res = Result{kPlaneBit | k, t};
      }
    }
    // A primitive at exactly the plane's t still wins (Scene::intersect).
    return res.prim == Result::kMiss
               ? t_max
               : std::nextafter(t_max, std::numeric_limits<float>::infinity());
  };
  const auto any_plane = [&](const Ray& r) {
    for (const std::uint32_t i : planes) {
      float t;
      if (intersect_plane(r, objects[i].plane_point, objects[i].plane_normal, r.t_max, t))
        return true;
    }
    return false;
  };
  const auto embree_closest = [&](const Ray& r) {
    Result res;
    const float t_max = nearest_plane(r, res);
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray = to_embree(r, t_max);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(es.closest, &ctx, &rh);
    return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID
               ? res
               : Result{es.prim(rh.hit.geomID, rh.hit.primID), rh.ray.tfar};
  };
  const auto embree_occluded = [&](const Ray& r) {
    if (any_plane(r)) return true;
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay e = to_embree(r, r.t_max);
    rtcOccluded1(es.any, &ctx, &e);
    return e.tfar < 0.0f;  // rtcOccluded1 sets tfar = -inf on a hit
  };
  // The same through `native` (Embree's own spheres).
  const auto native_closest = [&](const Ray& r) {
    Result res;
    const float t_max = nearest_plane(r, res);
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray = to_embree(r, t_max);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(es.native, &ctx, &rh);
    return rh.hit.geomID == RTC_INVALID_GEOMETRY_ID
               ? res
               : Result{es.native_prim(rh.hit.geomID, rh.hit.primID), rh.ray.tfar};
  };
  const auto native_occluded = [&](const Ray& r) {
    if (any_plane(r)) return true;
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRay e = to_embree(r, r.t_max);
    rtcOccluded1(es.native, &ctx, &e);
    return e.tfar < 0.0f;
  };
  // Embree's stream API (rtcIntersect1M / rtcOccluded1M) over the same rays, kStream at a time,
  // flagged coherent for camera rays and incoherent for the others (Embree may trace them as
  // packets); planes as above, per ray, before the call.
  constexpr std::size_t kStream = 256;
  const auto stream_closest = [&](const Ray* rays, std::size_t m, Result* out, bool coherent) {
    RTCRayHit rh[kStream];
    for (std::size_t j = 0; j < m; ++j) {
      out[j] = Result{};
      rh[j].ray = to_embree(rays[j], nearest_plane(rays[j], out[j]));
      rh[j].hit.geomID = RTC_INVALID_GEOMETRY_ID;
    }
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags =
        coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    rtcIntersect1M(es.closest, &ctx, rh, static_cast<unsigned>(m), sizeof(RTCRayHit));
    for (std::size_t j = 0; j < m; ++j)
      if (rh[j].hit.geomID != RTC_INVALID_GEOMETRY_ID)
        out[j] = Result{es.prim(rh[j].hit.geomID, rh[j].hit.primID), rh[j].ray.tfar};
  };
  const auto stream_occluded = [&](const Ray* rays, std::size_t m, Result* out) {
    RTCRay e[kStream];
    for (std::size_t j = 0; j < m; ++j) {
      out[j].prim = any_plane(rays[j]) ? 1 : 0;
      // a ray a plane already blocks is sent with an empty interval (tfar < tnear)
      e[j] = to_embree(rays[j], out[j].prim ? -1.0f : rays[j].t_max);
    }
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    rtcOccluded1M(es.any, &ctx, e, static_cast<unsigned>(m), sizeof(RTCRay));
    for (std::size_t j = 0; j < m; ++j)
      if (!out[j].prim && e[j].tfar < 0.0f) out[j].prim = 1;
  };
  const auto thaw_closest = [&](const Ray& r) {
    Hit h;
    return scene.intersect(r, h) ? Result{h.prim, h.t} : Result{};
  };

  std::size_t total_rays = 0, total_mismatch = 0, total_self = 0, cracks[2] = {0, 0};
  std::size_t near_origin = 0;
  Timing thaw_all{0, 0}, embree_all{0, 0}, thaw_photon{0, 0}, native_all{0, 0};
  std::size_t native_differ = 0, stream_differ = 0;
  std::vector<std::string> native_lines, stream_lines;
  Timing stream_all{0, 0};
  for (int k = 0; k < kKinds; ++k) {
    const std::vector<Ray>& rays = rec.rays[k];
    const std::size_t n = rays.size();
    if (n == 0) continue;
    std::vector<Result> a(n), b(n), c(es.native ? n : 0), d(n);
    Timing tt, te, tn, ts;
    for (int r = 0; r < repetitions; ++r) {  // interleaved: both see the same load
      if (any_hit(k)) {
        timed(tt, n, threads, [&](std::size_t i) { a[i].prim = scene.occluded(rays[i]) ? 1 : 0; });
        timed(te, n, threads, [&](std::size_t i) { b[i].prim = embree_occluded(rays[i]) ? 1 : 0; });
        if (es.native)
          timed(tn, n, threads,
                [&](std::size_t i) { c[i].prim = native_occluded(rays[i]) ? 1 : 0; });
        timed_chunks(ts, n, kStream, threads, [&](std::size_t b0, std::size_t b1) {
          stream_occluded(&rays[b0], b1 - b0, &d[b0]);
        });
      } else {
        timed(tt, n, threads, [&](std::size_t i) { a[i] = thaw_closest(rays[i]); });
        timed(te, n, threads, [&](std::size_t i) { b[i] = embree_closest(rays[i]); });
        if (es.native)
          timed(tn, n, threads, [&](std::size_t i) { c[i] = native_closest(rays[i]); });
        timed_chunks(ts, n, kStream, threads, [&](std::size_t b0, std::size_t b1) {
          stream_closest(&rays[b0], b1 - b0, &d[b0], k == kCamera);
        });
      }
    }
    {
      // The stream's answers are Embree's too (rtcIntersect1's, possibly traced as packets):
      // counted as the native spheres' below.
      std::size_t differ = 0;
      for (std::size_t i = 0; i < n; ++i)
        if (a[i].prim != d[i].prim &&
            (any_hit(k) || a[i].prim == Result::kMiss || d[i].prim == Result::kMiss ||
             std::fabs(a[i].t - d[i].t) > 1e-4f * std::max(a[i].t, d[i].t)))
          ++differ;
      char line[160];
      std::snprintf(line, sizeof line, "%-10s %9zu %15.2f %12.3f %12.3f %9zu", kKindName[k], n,
                    double(n) / ts.wall_s * 1e-6, ts.wall_s / tt.wall_s, ts.cpu_s / tt.cpu_s,
                    differ);
      stream_lines.push_back(line);
      stream_all.wall_s += ts.wall_s;
      stream_all.cpu_s += ts.cpu_s;
      stream_differ += differ;
    }
    if (es.native) {
      // Embree's own spheres answer with Embree's arithmetic: rays that differ from thaw's by
      // more than a rounding bound of t (either side hits and the other not, or t differs by
      // more than 1e-4 relative) are counted for information, not judged.
      std::size_t differ = 0;
      for (std::size_t i = 0; i < n; ++i)
        if (a[i].prim != c[i].prim &&
            (any_hit(k) || a[i].prim == Result::kMiss || c[i].prim == Result::kMiss ||
             std::fabs(a[i].t - c[i].t) > 1e-4f * std::max(a[i].t, c[i].t)))
          ++differ;
      char line[160];
      std::snprintf(line, sizeof line, "%-10s %9zu %15.2f %12.3f %12.3f %9zu", kKindName[k], n,
                    double(n) / tn.wall_s * 1e-6, tn.wall_s / tt.wall_s, tn.cpu_s / tt.cpu_s,
                    differ);
      native_lines.push_back(line);
      native_all.wall_s += tn.wall_s;
      native_all.cpu_s += tn.cpu_s;
      native_differ += differ;
    }
    std::size_t mismatch = 0, self = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (a[i].prim == b[i].prim) continue;
      Result ta = a[i], eb = b[i];
      if (any_hit(k)) {  // which primitive the occluding side met: its closest hit
        ta = ta.prim ? thaw_closest(rays[i]) : Result{};
        eb = eb.prim ? embree_closest(rays[i]) : Result{};
      }
      const bool thaw_hit = ta.prim != Result::kMiss, embree_hit = eb.prim != Result::kMiss;
      if (embree_hit && (!thaw_hit || eb.t < ta.t) && self_hit(rays[i], eb.prim, eb.t)) {
        ++self;
        continue;
      }
      if (thaw_hit && embree_hit) {
        const float tol =
            2 * g16 * (extent + length(abs(rays[i].origin))) / length(rays[i].direction);
        if (any_hit(k) || std::fabs(ta.t - eb.t) <= tol) continue;  // a shared edge
      } else if (embree_hit && t_bound_rejected(rays[i], eb.prim, eb.t)) {
        ++near_origin;
        continue;
      }
      // One side's hit is the nearer (or the only) one and lies on an edge: the other passed
      // through a crack there (cracks[0]: thaw did, cracks[1]: Embree did).
      const bool thaw_nearer = thaw_hit && (!embree_hit || ta.t < eb.t);
      const Result& nearer = thaw_nearer ? ta : eb;
      if (!any_hit(k) && nearer.prim != Result::kMiss && at_edge(rays[i], nearer.prim)) {
        ++cracks[thaw_nearer ? 1 : 0];
        continue;
      }
      if (mismatch < 5) {
        std::fprintf(stderr, "  %s ray %zu: thaw prim %u t %.9g, Embree prim %u t %.9g\n",
                     kKindName[k], i, ta.prim, double(ta.t), eb.prim, double(eb.t));
        const Ray& r = rays[i];
        std::fprintf(stderr, "    origin %.9g %.9g %.9g direction %.9g %.9g %.9g t_max %.9g\n",
                     double(r.origin.x), double(r.origin.y), double(r.origin.z),
                     double(r.direction.x), double(r.direction.y), double(r.direction.z),
                     double(r.t_max));
        for (const Result& x : {ta, eb})
          if (x.prim != Result::kMiss && is_triangle(x.prim)) {
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
    for (auto [sum, part] : {std::pair{&thaw_all, &tt}, std::pair{&embree_all, &te}}) {
      sum->wall_s += part->wall_s;
      sum->cpu_s += part->cpu_s;
    }
    if (k == kPhoton || k == kPhotonShadow) thaw_photon.cpu_s += tt.cpu_s;
  }
  std::printf("%-10s %9zu %14.2f %15.2f %12.3f %12.3f %9zu %10zu\n", "all", total_rays,
              double(total_rays) / thaw_all.wall_s * 1e-6,
              double(total_rays) / embree_all.wall_s * 1e-6, embree_all.wall_s / thaw_all.wall_s,
              embree_all.cpu_s / thaw_all.cpu_s, total_mismatch, total_self);
  std::printf(
      "Embree's stream API (rtcIntersect1M / rtcOccluded1M, %zu rays a call, camera rays flagged "
      "coherent):\n%-10s %9s %15s %12s %12s %9s\n",
      kStream, "rays", "count", "Embree [Mray/s]", "thaw/Embree", "(CPU-time)", "differ");
  for (const std::string& l : stream_lines) std::printf("%s\n", l.c_str());
  std::printf("%-10s %9zu %15.2f %12.3f %12.3f %9zu\n", "all", total_rays,
              double(total_rays) / stream_all.wall_s * 1e-6, stream_all.wall_s / thaw_all.wall_s,
              stream_all.cpu_s / thaw_all.cpu_s, stream_differ);
  if (es.native) {
    std::printf(
        "Embree with its own sphere primitives (RTC_GEOMETRY_TYPE_SPHERE_POINT; its answers, "
        "not thaw's exact ones):\n%-10s %9s %15s %12s %12s %9s\n",
        "rays", "count", "Embree [Mray/s]", "thaw/Embree", "(CPU-time)", "differ");
    for (const std::string& l : native_lines) std::printf("%s\n", l.c_str());
    std::printf("%-10s %9zu %15.2f %12.3f %12.3f %9zu\n", "all", total_rays,
                double(total_rays) / native_all.wall_s * 1e-6, native_all.wall_s / thaw_all.wall_s,
                native_all.cpu_s / thaw_all.cpu_s, native_differ);
  }
  const double frame_per_cpu = double(total_rays) / frame.cpu_s * 1e-6;
  const double embree_per_cpu = double(total_rays) / embree_all.cpu_s * 1e-6;
  std::printf(
      "frame: %.3f s wall, %.3f CPU-s (photon pass included), %.2f Mrays per CPU-second = %.3f of "
      "Embree's replay of the same rays (%.2f Mrays per CPU-second)\n",
      frame.wall_s, frame.cpu_s, frame_per_cpu, frame_per_cpu / embree_per_cpu, embree_per_cpu);
  // Where the frame's CPU time goes: the replays measure traversal alone (the same queries the
  // frame makes, answered by the same code); the photon pass and the PNG are timed alone; the
  // rest is the frame's own work between its queries.
  const double photon_other = std::max(0.0, photons.cpu_s - thaw_photon.cpu_s);
  const double rest = frame.cpu_s - thaw_all.cpu_s - photon_other;
  std::printf(
      "frame CPU time (best of %d each, %d threads): traversal %.3f s (%.0f %%: frame rays %.3f, "
      "photon rays %.3f), photon pass outside its traversal %.3f s (%.0f %%; the pass %.3f s in "
      "all), camera sampling + shading + film %.3f s (%.0f %%); the PNG (not in the frame) %.3f "
      "CPU-s = %.0f %% of the frame\n",
      std::max(1, repetitions / 2), threads, thaw_all.cpu_s, 100 * thaw_all.cpu_s / frame.cpu_s,
      thaw_all.cpu_s - thaw_photon.cpu_s, thaw_photon.cpu_s, photon_other,
      100 * photon_other / frame.cpu_s, photons.cpu_s, rest, 100 * rest / frame.cpu_s, png.cpu_s,
      100 * png.cpu_s / frame.cpu_s);
  if (total_self > 0)
    std::printf(
        "self-hits: %zu rays Embree found re-hitting the triangle they start on, at t "
        "within rounding (thaw's offset origins exclude these); not counted as mismatches\n",
        total_self);
  if (near_origin > 0)
    std::printf(
        "t bound: %zu rays met a large triangle nearer than thaw's rounding bound of t there "
        "(thaw rejects such hits, Embree reports them); not counted as mismatches\n",
        near_origin);
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
