#pragma once
// Optional recording of the rays given to the scene's BVH queries (Scene::intersect, closest hit,
// and Scene::occluded, any hit), for bench/render/ray_limit (issue 30), which replays a frame's
// rays through thaw's BVH and through Embree. Off by default: a query then pays one relaxed load
// of a null pointer and a branch that is never taken; nothing the queries return changes either
// way. Knows nothing about scenes, shapes or who records.
#include <atomic>
#include <cstdint>

#include "render/math/ray.h"

namespace thaw::render {

enum class RayQuery : std::uint8_t { closest, any };

/// Receives every query's ray while installed. record() is called from the rendering threads:
/// it must be thread-safe and must not throw.
class RayRecorder {
 public:
  virtual ~RayRecorder() = default;
  virtual void record(RayQuery query, const Ray& ray) noexcept = 0;
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

}  // namespace thaw::render
