#pragma once
// Optional recording of the rays given to the scene's BVH queries (Scene::intersect, closest hit,
// and Scene::occluded, any hit), for bench/render/ray_limit (issue 30), which replays a frame's
// rays through thaw's BVH and through Embree; the caustic photon pass marks its queries as the
// photon stream (mark_ray_stream) so that they can be told from the frame's. Off by default: a
// query then pays one relaxed load of a null pointer and a branch that is never taken; nothing the
// queries return changes either way. Knows nothing about scenes, shapes or who records.
#include <atomic>
#include <cstdint>

#include "render/math/ray.h"

namespace thaw::render {

enum class RayQuery : std::uint8_t { closest, any };

/// What the queries recorded next serve: the frame's own rays (camera, reflection, refraction,
/// shadow) or the caustic photon pass's (render/photon), which runs before the frame's tiles.
enum class RayStream : std::uint8_t { frame, photon };

/// Receives every query's ray while installed. record() is called from the rendering threads:
/// it must be thread-safe and must not throw.
class RayRecorder {
 public:
  virtual ~RayRecorder() = default;
  virtual void record(RayQuery query, const Ray& ray) noexcept = 0;
  /// Told when the queries start serving another stream (between passes, not during one).
  virtual void stream(RayStream) noexcept {}
};

namespace detail {
inline std::atomic<RayRecorder*> g_ray_recorder{nullptr};
}

/// Installs `recorder` (nullptr: off). Not to be changed while a frame renders.
inline void set_ray_recorder(RayRecorder* recorder) {
  detail::g_ray_recorder.store(recorder, std::memory_order_release);
}

/// Hands `ray` to the installed recorder, if any.
inline void record_ray(RayQuery query, const Ray& ray) {
  if (RayRecorder* r = detail::g_ray_recorder.load(std::memory_order_relaxed)) [[unlikely]]
    r->record(query, ray);
}

/// Tells the installed recorder, if any, that the queries now serve `stream`.
inline void mark_ray_stream(RayStream stream) {
  if (RayRecorder* r = detail::g_ray_recorder.load(std::memory_order_relaxed)) [[unlikely]]
    r->stream(stream);
}

/// Marks `stream` for its lifetime, then RayStream::frame again (also when an exception leaves).
class RayStreamScope {
 public:
  explicit RayStreamScope(RayStream stream) { mark_ray_stream(stream); }
  ~RayStreamScope() { mark_ray_stream(RayStream::frame); }
  RayStreamScope(const RayStreamScope&) = delete;
  RayStreamScope& operator=(const RayStreamScope&) = delete;
};

}  // namespace thaw::render
