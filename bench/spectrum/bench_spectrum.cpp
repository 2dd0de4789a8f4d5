// Cost of the spectral pieces per camera sample / per shading event, single thread: wavelength
// sampling, RGB uplifting of a reflectance and of a light, n(lambda) for each index model,
// Beer-Lambert transmittance, and the film's spectrum -> XYZ -> sRGB conversion.
#include <benchmark/benchmark.h>

#include "render/format/medium_library.h"
#include "render/media/medium.h"
#include "render/spectrum/colour.h"
#include "render/spectrum/rgb_uplift.h"
#include "render/spectrum/sampled_wavelengths.h"

namespace {

using namespace thaw::render;

/// A cheap deterministic stream of numbers in [0, 1).
struct Stream {
  double x = 0.1234;
  double next() {
    x += 0.6180339887498949;
    if (x >= 1) x -= 1;
    return x;
  }
};

void BM_SampleWavelengthsVisible(benchmark::State& state) {
  Stream s;
  for (auto _ : state)
    benchmark::DoNotOptimize(SampledWavelengths::sample(s.next(), HeroDensity::visible));
}
BENCHMARK(BM_SampleWavelengthsVisible);

void BM_SampleWavelengthsUniform(benchmark::State& state) {
  Stream s;
  for (auto _ : state)
    benchmark::DoNotOptimize(SampledWavelengths::sample(s.next(), HeroDensity::uniform));
}
BENCHMARK(BM_SampleWavelengthsUniform);

void BM_UpliftReflectance(benchmark::State& state) {
  Stream s;
  const auto w = SampledWavelengths::sample(0.3);
  for (auto _ : state) {
    const RgbReflectanceSpectrum r({s.next(), 0.5, 0.2});
    benchmark::DoNotOptimize(r.sample(w));
  }
}
BENCHMARK(BM_UpliftReflectance);

void BM_UpliftIlluminant(benchmark::State& state) {
  Stream s;
  const auto w = SampledWavelengths::sample(0.3);
  for (auto _ : state) {
    const RgbIlluminantSpectrum l({1.0, s.next(), 0.8});
    benchmark::DoNotOptimize(l.sample(w));
  }
}
BENCHMARK(BM_UpliftIlluminant);

void BM_SpectrumToLinearSrgb(benchmark::State& state) {
  Stream s;
  for (auto _ : state) {
    const auto w = SampledWavelengths::sample(s.next());
    benchmark::DoNotOptimize(spectrum_to_linear_srgb(SampledSpectrum(0.5f), w));
  }
}
BENCHMARK(BM_SpectrumToLinearSrgb);

void BM_IndexOfRefraction(benchmark::State& state, const char* preset) {
  const media::Medium m = media::build_medium(*media::find_medium_preset(preset));
  Stream s;
  for (auto _ : state) {
    const auto w = SampledWavelengths::sample(s.next());
    benchmark::DoNotOptimize(m.n(w));
  }
}
BENCHMARK_CAPTURE(BM_IndexOfRefraction, sellmeier_3_terms, "n-sf10");
BENCHMARK_CAPTURE(BM_IndexOfRefraction, table_43_rows, "ice-ih");
BENCHMARK_CAPTURE(BM_IndexOfRefraction, iapws97, "water-0c");

void BM_Transmittance(benchmark::State& state) {
  const media::Medium m = media::build_medium(*media::find_medium_preset("water-20c"));
  Stream s;
  for (auto _ : state) {
    const auto w = SampledWavelengths::sample(s.next());
    benchmark::DoNotOptimize(m.transmittance(0.05, w));
  }
}
BENCHMARK(BM_Transmittance);

}  // namespace

BENCHMARK_MAIN();
