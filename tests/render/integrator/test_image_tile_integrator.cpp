// Tests render/integrator/image_tile_integrator.h with a worker that records what it is asked:
// every pixel gets exactly its samples, through its own sample positions, whatever the tile size
// and thread count, and progress is told once per tile.
#include "render/integrator/image_tile_integrator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>

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

/// A worker whose samples see a bright disc of radius `radius_px` pixels centred on the camera
/// ray `centre` (distances measured as angles over the camera's pixel angle: at the middle of a
/// narrow view, pixels to within 1e-4).
class DiscWorker {
 public:
  using Sample = Rgb;
  DiscWorker(const Scene& scene, Vec3 centre, float radius_px)
      : m_centre(centre), m_pixel_angle(scene.camera().pixel_angle()), m_radius(radius_px) {}
  float distance_px(const Vec3& d) const {
    return std::acos(std::clamp(dot(normalize(d), m_centre), -1.0f, 1.0f)) / m_pixel_angle;
  }
  void start_pixel(Pcg32&) {}
  Rgb sample(const Ray& r, const CameraSampleContext&, Pcg32&) {
    return Rgb::gray(distance_px(r.direction) < m_radius ? 0.8f : 0.05f);
  }
  static Rgb pixel_value(const Rgb& s, int samples) { return s * (1.0f / float(samples)); }
  void add_counts(RenderStats&) const {}

 private:
  Vec3 m_centre;
  float m_pixel_angle, m_radius;
};

TEST(ImageTileIntegrator, APixelWhosePairAgreesButStandsOutIsLookedAtAgain) {
  // The speck case: a bright disc a little wider than pixel (c, c) in the middle of a 9 x 9
  // image, so that both samples of the pixel's first pair fall inside it and agree (its first
  // batch stops at 2 with the full brightness) while its true (box-filtered) value is the disc's
  // share of the pixel, less than 1: the pixel stood alone 3 thresholds above its dark
  // neighbours. It must be looked at again, to the cap (it really is a peak: every look still
  // stands out), so that it holds exactly the estimate of 64 samples, which a stratified net
  // brings within a few hundredths of the disc's share (the 2-sample value: 0.8, far above).
  SceneDescription d;
  d.image.width = 9;
  d.image.height = 9;
  d.image.samples_per_pixel = 64;
  d.image.min_samples = 2;
  d.image.adaptive_threshold = 0.01;
  d.image.filter = FilterKind::box;
  d.image.filter_radius = 0.5;
  d.camera.position = {0.0, 0.0, 1.0};
  d.camera.look_at = {0.0, 0.0, 0.0};
  d.camera.up = {0.0, 1.0, 0.0};
  d.camera.vertical_fov_deg = 10.0;
  const Scene scene = build_scene(d);
  const int c = 4;
  const Vec3 centre = normalize(scene.camera().generate(c + 0.5f, c + 0.5f).direction);
  // The disc's radius: just beyond the farther of the pixel's first two samples (within the
  // pixel's half-diagonal, so its corners stay dark).
  const DiscWorker probe(scene, centre, 0.0f);
  const sampling::PixelSampler points(c, c, 0);
  const Filter box(FilterKind::box, 0.5);
  float farthest = 0.0f;
  for (std::uint32_t i = 0; i < 2; ++i) {
    const FilterSample fs = box.sample(points.get_2d(i, kFilmDimension));
    farthest = std::max(
        farthest,
        probe.distance_px(scene.camera().generate(c + 0.5f + fs.dx, c + 0.5f + fs.dy).direction));
  }
  ASSERT_LT(farthest, 0.6f) << "the sampler's first pair of this pixel changed: pick another";
  const float radius = std::max(farthest + 0.02f, 0.55f);
  const DiscWorker disc(scene, centre, radius);
  // The pixel estimated alone: adaptive (as the first pass does), and with all 64 samples.
  const auto alone = [&](const AntialiasingSettings& aa) {
    DiscWorker w(disc);
    Pcg32 rng(0);
    return estimate_pixel<Rgb>(
        c, c, points, box, aa,
        [&](float fx, float fy, std::uint32_t s) {
          return w.sample(scene.camera().generate(fx, fy), CameraSampleContext{&points, s}, rng);
        },
        [](const Rgb& v) { return v; });
  };
  AntialiasingSettings aa = antialiasing_settings(scene.settings());
  const auto first = alone(aa);
  EXPECT_EQ(first.samples, 2);
  EXPECT_FLOAT_EQ(first.value.g, 0.8f);
  aa.adaptive = false;
  const auto capped = alone(aa);
  // The disc's exact share of the pixel, by a 400 x 400 midpoint grid.
  double inside = 0.0;
  for (int j = 0; j < 400; ++j)
    for (int i = 0; i < 400; ++i)
      inside +=
          disc.distance_px(
              scene.camera().generate(c + (i + 0.5f) / 400.0f, c + (j + 0.5f) / 400.0f).direction) <
                  radius
              ? 1.0
              : 0.0;
  const double exact = 0.05 + 0.75 * inside / (400.0 * 400.0);
  EXPECT_LT(std::abs(capped.value.g - exact), 0.25 * std::abs(first.value.g - exact));
  RenderOptions o;
  o.threads = 2;
  o.tile_size = 4;
  const RenderResult r = render_image_tiles(scene, o, {}, [&] { return DiscWorker(disc); });
  EXPECT_EQ(r.image.at(c, c).g, capped.value.g);
  // The same image for any thread count and tiling.
  o.threads = 1;
  o.tile_size = 16;
  const RenderResult r1 = render_image_tiles(scene, o, {}, [&] { return DiscWorker(disc); });
  for (std::size_t i = 0; i < r.image.pixels().size(); ++i)
    ASSERT_EQ(r.image.pixels()[i].g, r1.image.pixels()[i].g) << i;
  EXPECT_EQ(r.stats.camera_samples, r1.stats.camera_samples);
}

}  // namespace
}  // namespace thaw::render
