// Image writing on S4 (16 spheres over a floor, data/scenes/s4_spheres16.toml) rendered once at
// 2000x2000, as bench/render/compare_povray.sh renders it: the whole encode_png (sRGB + filter +
// deflate) of thaw's banded parallel encoder (render/image/png_encoder.h) at zlib levels 1, 2
// and 6 on 1 and 2 threads, against the single-threaded stb_image_write encoder thaw used before
// (level 2 and stb's default 8), 16-bit PNG, PFM and EXR; and, when OpenImageIO is installed
// (Debian libopenimageio-dev, bench only), OpenImageIO's PNG (libpng; its default zlib level 6,
// and level 2) and EXR writers on the same pixels, for the choice of image library (docs/render.md
// "Output formats"). OpenImageIO writes to a file in /dev/shm (memory), thaw to a string.
// Counters: output megabytes. Figures: docs/benchmarks.md.
#include <benchmark/benchmark.h>
#include <omp.h>
#include <stb/stb_image_write.h>

#include <filesystem>
#include <string>
#include <vector>
#ifdef THAW_HAVE_OIIO
#include <OpenImageIO/imageio.h>
#endif

#include "render/format/scene_parser.h"
#include "render/image/exr_io.h"
#include "render/image/image_io.h"
#include "render/image/png_encoder.h"
#include "render/integrator/aov_pass.h"
#include "render/integrator/whitted.h"
#include "render/scene/scene.h"

namespace thaw::render {
namespace {

struct S4 {
  Image image;
  AovImage aovs;
  std::vector<std::uint8_t> srgb8;
  S4() {
    SceneDescription d =
        parse_scene_file(std::string(THAW_SOURCE_DIR) + "/data/scenes/s4_spheres16.toml");
    d.image.width = d.image.height = 2000;
    const Scene scene = build_scene(d);
    image = render(scene).image;
    aovs = render_aovs(scene);
    srgb8.resize(image.pixels().size() * 3);
    for (std::size_t i = 0; i < image.pixels().size(); ++i) {
      srgb8[3 * i] = srgb8_by_table(image.pixels()[i].r);
      srgb8[3 * i + 1] = srgb8_by_table(image.pixels()[i].g);
      srgb8[3 * i + 2] = srgb8_by_table(image.pixels()[i].b);
    }
  }
};
const S4& s4() {
  static const S4 s;
  return s;
}

void BM_ThawPng(benchmark::State& state) {
  const S4& s = s4();
  const PngLayout layout{2000, 2000, 3, 8, static_cast<int>(state.range(0))};
  std::size_t bytes = 0;
  for (auto _ : state)
    bytes = encode_png_samples(s.srgb8.data(), layout, static_cast<int>(state.range(1))).size();
  state.counters["MB"] = bytes * 1e-6;
}
BENCHMARK(BM_ThawPng)
    ->ArgsProduct({{1, 2, 6}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_StbPng(benchmark::State& state) {
  const S4& s = s4();
  stbi_write_png_compression_level = static_cast<int>(state.range(0));
  std::size_t bytes = 0;
  for (auto _ : state) {
    std::string out;
    stbi_write_png_to_func(
        [](void* ctx, void* data, int size) {
          static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), size);
        },
        &out, 2000, 2000, 3, s.srgb8.data(), 2000 * 3);
    bytes = out.size();
  }
  state.counters["MB"] = bytes * 1e-6;
}
BENCHMARK(BM_StbPng)->Arg(2)->Arg(8)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The whole float image to file bytes, as `thaw render -o` does (sRGB encoding included).
void BM_EncodePng(benchmark::State& state) {
  const S4& s = s4();
  std::size_t bytes = 0;
  for (auto _ : state) bytes = encode_png(s.image, 0.0, static_cast<int>(state.range(0))).size();
  state.counters["MB"] = bytes * 1e-6;
}
BENCHMARK(BM_EncodePng)->Arg(8)->Arg(16)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_EncodePfm(benchmark::State& state) {
  const S4& s = s4();
  std::size_t bytes = 0;
  for (auto _ : state) bytes = encode_pfm(s.image).size();
  state.counters["MB"] = bytes * 1e-6;
}
BENCHMARK(BM_EncodePfm)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_EncodeExr(benchmark::State& state) {
  const S4& s = s4();
  std::size_t bytes = 0;
  const bool with_aovs = state.range(0) != 0;
  for (auto _ : state)
    bytes = encode_exr(s.image, with_aovs ? &s.aovs : nullptr, ExrMetadata{}).size();
  state.counters["MB"] = bytes * 1e-6;
}
BENCHMARK(BM_EncodeExr)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_AovPass(benchmark::State& state) {
  SceneDescription d =
      parse_scene_file(std::string(THAW_SOURCE_DIR) + "/data/scenes/s4_spheres16.toml");
  d.image.width = d.image.height = 2000;
  const Scene scene = build_scene(d);
  for (auto _ : state) benchmark::DoNotOptimize(render_aovs(scene).depth.data());
}
BENCHMARK(BM_AovPass)->Unit(benchmark::kMillisecond)->UseRealTime();

#ifdef THAW_HAVE_OIIO
/// OpenImageIO writing `spec`-typed pixels to /dev/shm; returns the file size.
std::size_t oiio_write(const std::string& name, OIIO::ImageSpec spec, OIIO::TypeDesc type,
                       const void* pixels) {
  const std::string path = "/dev/shm/thaw_bench_oiio_" + name;
  auto out = OIIO::ImageOutput::create(path);
  if (!out || !out->open(path, spec) || !out->write_image(type, pixels)) return 0;
  out->close();
  return std::filesystem::file_size(path);
}

void BM_OiioPng(benchmark::State& state) {
  const S4& s = s4();
  OIIO::ImageSpec spec(2000, 2000, 3, OIIO::TypeDesc::UINT8);
  if (state.range(0) > 0) spec.attribute("png:compressionLevel", static_cast<int>(state.range(0)));
  std::size_t bytes = 0;
  for (auto _ : state) bytes = oiio_write("s4.png", spec, OIIO::TypeDesc::UINT8, s.srgb8.data());
  state.counters["MB"] = bytes * 1e-6;
}
// 0: OpenImageIO's default level
BENCHMARK(BM_OiioPng)->Arg(0)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_OiioExr(benchmark::State& state) {
  const S4& s = s4();
  OIIO::ImageSpec spec(2000, 2000, 3, OIIO::TypeDesc::HALF);
  spec.attribute("compression", "zip");
  std::size_t bytes = 0;
  for (auto _ : state)
    bytes = oiio_write("s4.exr", spec, OIIO::TypeDesc::FLOAT, s.image.pixels().data());
  state.counters["MB"] = bytes * 1e-6;
}
BENCHMARK(BM_OiioExr)->Unit(benchmark::kMillisecond)->UseRealTime();
#endif

}  // namespace
}  // namespace thaw::render

BENCHMARK_MAIN();
