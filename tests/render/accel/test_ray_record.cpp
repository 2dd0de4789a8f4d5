// Tests render/accel/ray_record.h: an installed recorder sees every Scene::intersect (closest) and
// Scene::occluded (any) query's ray as given, the queries answer the same with and without it, and
// nothing is recorded once it is removed.
#include "render/accel/ray_record.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "render/scene/scene.h"
#include "tests/render/test_util.h"

namespace thaw::render {
namespace {

struct Log final : RayRecorder {
  std::vector<std::pair<RayQuery, Ray>> rays;
  void record(RayQuery query, const Ray& ray) noexcept override { rays.emplace_back(query, ray); }
};

TEST(RayRecord, SeesEveryQueryAndChangesNoAnswer) {
  SceneDescription d;
  d.camera.position = {0, 0, 5};
  d.camera.look_at = {0, 0, 0};
  d.media = {test::medium("air", 1.0), test::medium("ice", 1.31)};
  d.add_dielectric_mesh(std::make_shared<TriangleMesh>(test::icosphere(2, 1.0f)), "ice", "air",
                        "shell");
  const Scene s = build_scene(d);
  const Ray through{{0, 0, 5}, {0, 0, -1}};      // meets the shell
  const Ray past{{0, 3, 5}, {0, 0, -1}, 20.0f};  // misses it
  Hit off_hit;
  const bool off_found = s.intersect(through, off_hit);
  const bool off_blocked = s.occluded(through), off_past = s.occluded(past);

  Log log;
  set_ray_recorder(&log);
  Hit on_hit;
  const bool on_found = s.intersect(through, on_hit);
  const bool on_blocked = s.occluded(through), on_past = s.occluded(past);
  set_ray_recorder(nullptr);

  EXPECT_TRUE(off_found);
  EXPECT_EQ(on_found, off_found);
  EXPECT_EQ(on_hit.prim, off_hit.prim);
  EXPECT_EQ(on_hit.t, off_hit.t);
  EXPECT_TRUE(off_blocked);
  EXPECT_FALSE(off_past);
  EXPECT_EQ(on_blocked, off_blocked);
  EXPECT_EQ(on_past, off_past);
  ASSERT_EQ(log.rays.size(), 3u);
  EXPECT_EQ(log.rays[0].first, RayQuery::closest);
  EXPECT_EQ(log.rays[1].first, RayQuery::any);
  EXPECT_EQ(log.rays[2].first, RayQuery::any);
  EXPECT_EQ(log.rays[0].second.origin, through.origin);
  EXPECT_EQ(log.rays[0].second.direction, through.direction);
  EXPECT_EQ(log.rays[2].second.origin, past.origin);
  EXPECT_EQ(log.rays[2].second.t_max, past.t_max);

  Hit h;
  (void)s.intersect(through, h);
  (void)s.occluded(past);
  EXPECT_EQ(log.rays.size(), 3u);  // removed: nothing more
}

}  // namespace
}  // namespace thaw::render
