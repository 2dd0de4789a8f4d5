// Tests render/integrator/image_tile_integrator.h with a worker that records what it is asked:
// every pixel gets exactly its samples, through its own sample positions, whatever the tile size
// and thread count, and progress is told once per tile.
#include "render/integrator/image_tile_integrator.h"

#include <gtest/gtest.h>

#include <atomic>

namespace thaw::render {
namespace {

/// Without adaptivity, with a box filter (weight 1): every pixel takes exactly `spp` samples.
Scene small_scene(int w, int h, int spp) {
  SceneDescription d;
  d.image.width = w;
  d.image.height = h;
  d.image.samples_per_pixel = spp;
  d.image.adaptive = false;
  d.image.filter = FilterKind::box;
  d.image.filter_radius = 0.5;
  d.camera.position = {0.0, 0.0, 1.0};
  d.camera.look_at = {0.0, 0.0, 0.0};
  d.camera.up = {0.0, 1.0, 0.0};
  return build_scene(d);
}

/// Sample value: the camera ray's direction and a count; the pixel value is their mean (so each
/// pixel's colour says which rays it was given) with the mean count (1: weights average to 1) in
/// the blue channel.
class RecordingWorker {
 public:
  struct Sample {
    Vec3 direction;
    float count = 0;
    Sample& operator+=(const Sample& o) {
      direction = direction + o.direction;
      count += o.count;
      return *this;
    }
    Sample operator*(float f) const { return {direction * f, count * f}; }
  };
  void start_pixel(Pcg32&) { ++m_pixels; }
  Sample sample(const Ray& r, const CameraSampleContext&, Pcg32&) {
    ++m_rays;
    return {r.direction, 1.0f};
  }
  static Rgb pixel_value(const Sample& s, int samples) {
    return {s.direction.x / float(samples), s.direction.y / float(samples), s.count};
  }
  void add_counts(RenderStats& stats) const { stats.rays += m_rays; }

 private:
  std::uint64_t m_rays = 0, m_pixels = 0;
};

TEST(ImageTileIntegrator, EveryPixelGetsItsSamplesOnce) {
  const Scene scene = small_scene(37, 21, 3);
  RenderOptions o;
  o.tile_size = 8;
  o.threads = 2;
  std::atomic<int> calls{0};
  const RenderResult r = render_image_tiles(
      scene, o,
      [&](std::int64_t, std::int64_t total) {
        ++calls;
        EXPECT_EQ(total, 5 * 3);
      },
      [] { return RecordingWorker(); });
  EXPECT_EQ(calls.load(), 5 * 3);
  EXPECT_EQ(r.stats.rays, 37u * 21u * 3u);
  EXPECT_EQ(r.stats.camera_samples, 37u * 21u * 3u);
  for (int y = 0; y < 21; ++y)
    for (int x = 0; x < 37; ++x) ASSERT_EQ(r.image.at(x, y).b, 1.0f) << x << " " << y;
  // The mean direction of the samples points into the pixel: left pixels look left, etc.
  EXPECT_LT(r.image.at(0, 10).r, r.image.at(36, 10).r);
}

TEST(ImageTileIntegrator, ImageIndependentOfTilesAndThreads) {
  const Scene scene = small_scene(29, 17, 5);
  RenderOptions a, b;
  a.tile_size = 16;
  a.threads = 1;
  b.tile_size = 5;
  b.threads = 3;
  const RenderResult ra = render_image_tiles(scene, a, {}, [] { return RecordingWorker(); });
  const RenderResult rb = render_image_tiles(scene, b, {}, [] { return RecordingWorker(); });
  ASSERT_EQ(ra.image.pixels().size(), rb.image.pixels().size());
  for (std::size_t i = 0; i < ra.image.pixels().size(); ++i) {
    ASSERT_EQ(ra.image.pixels()[i].r, rb.image.pixels()[i].r) << i;
    ASSERT_EQ(ra.image.pixels()[i].g, rb.image.pixels()[i].g) << i;
  }
}

/// A worker whose samples are all the same colour: nothing varies within a pixel.
class FlatWorker {
 public:
  using Sample = Rgb;
  void start_pixel(Pcg32&) {}
  Rgb sample(const Ray&, const CameraSampleContext&, Pcg32&) { return {0.25f, 0.5f, 0.75f}; }
  static Rgb pixel_value(const Rgb& s, int samples) { return s * (1.0f / float(samples)); }
  void add_counts(RenderStats&) const {}
};

TEST(ImageTileIntegrator, AdaptiveFilmStopsAfterTheFirstBatchWhereNothingVaries) {
  SceneDescription d;
  d.image.width = 8;
  d.image.height = 8;
  d.image.samples_per_pixel = 64;
  d.image.min_samples = 4;
  d.image.filter = FilterKind::box;  // weight 1: the mean is the colour itself
  d.image.filter_radius = 0.5;
  const Scene adaptive = build_scene(d);
  const RenderResult r = render_image_tiles(adaptive, {}, {}, [] { return FlatWorker(); });
  EXPECT_EQ(r.stats.camera_samples, 8u * 8u * 4u);
  EXPECT_FLOAT_EQ(r.image.at(3, 5).g, 0.5f);
  d.image.adaptive = false;
  const Scene fixed = build_scene(d);
  EXPECT_EQ(render_image_tiles(fixed, {}, {}, [] { return FlatWorker(); }).stats.camera_samples,
            8u * 8u * 64u);
}

}  // namespace
}  // namespace thaw::render
