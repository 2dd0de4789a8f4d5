// The photon pass; see caustic_map.h.
#include "render/photon/caustic_map.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <new>
#include <vector>

#include "base/interrupt.h"
#include "render/accel/ray_record.h"
#include "render/photon/light_cone.h"
#include "render/photon/low_discrepancy.h"
#include "render/photon/photon_tracer.h"
#include "render/spectrum/colour.h"
#include "render/spectrum/rgb_uplift.h"
#include "render/spectrum/sampled_wavelengths.h"

namespace thaw::render::photon {

namespace {

/// Photons per parallel work item: fixed, so the storage order never depends on the threads.
constexpr long long kChunk = 4096;

double luminance(const Rgb& c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

struct ChunkResult {
  std::vector<Photon> photons;
  /// target of each photon
  std::vector<std::uint32_t> target;
  long long traced = 0;
  std::uint64_t rays = 0;
  Flux emitted, stored, direct, escaped, absorbed, stopped, cut, roulette, roulette_variance;
};

/// What a cone's photons need besides the cone.
struct ConePlan {
  LightCone cone;
  long long first = 0, count = 0;
  /// Phi / (light colour) per photon: Omega / N, times D^2 for lights without falloff
  double scale = 0;
  /// spectral scenes: per channel, the light's colour over the mean sRGB of the cone's photon
  /// wavelengths (photon_colour), so that they sum to the light's colour exactly
  Rgb normalise{1.0f, 1.0f, 1.0f};
  std::uint32_t medium = 0;
};

/// Spectral photon i of a cone: its wavelength [nm] (Halton dimension 2, the film's visible
/// density p) and the linear sRGB of the light's spectrum S there, M (S(lambda) cmf(lambda)) /
/// p(lambda): on average over the photons, the light's colour.
Rgb photon_colour(const RgbIlluminantSpectrum& light, std::uint64_t i, double& lambda) {
  lambda = SampledWavelengths::sample(ScrambledHalton::sample(i, 2)).lambda_nm(0);
  const double s = light(lambda) / SampledWavelengths::hero_pdf(lambda, HeroDensity::visible);
  const Xyz bar = cie_xyz_bar(lambda);
  const LinearSrgb c = xyz_to_linear_srgb({bar.x * s, bar.y * s, bar.z * s});
  return {float(c.r), float(c.g), float(c.b)};
}

/// The ratio estimator of the light's colour over a cone's photon wavelengths (ConePlan): exact
/// for light that meets only wavelength-independent interfaces (grey scenes then match the RGB
/// renderer), consistent with O(1/N) bias otherwise, as the spectral film's ratio mode. A
/// channel the light (almost) lacks is left as sampled (a red light's dispersed photons keep
/// their small green and blue).
Rgb colour_normalisation(const RgbIlluminantSpectrum& light, const Rgb& colour, long long count) {
  double sum[3] = {0, 0, 0};
  for (long long i = 0; i < count; ++i) {
    double lambda;
    const Rgb c = photon_colour(light, static_cast<std::uint64_t>(i), lambda);
    sum[0] += c.r;
    sum[1] += c.g;
    sum[2] += c.b;
  }
  const float want[3] = {colour.r, colour.g, colour.b};
  const float peak = colour.max_component();
  float f[3];
  for (int k = 0; k < 3; ++k)
    f[k] = want[k] > 1e-3f * peak && sum[k] > 0 ? float(double(want[k]) * double(count) / sum[k])
                                                : 1.0f;
  return {f[0], f[1], f[2]};
}

Flux flux_of(const Rgb& c, double w) {
  return {c.r * w, c.g * w, c.b * w};
}

/// Splits `total` photons among the cones in proportion to sqrt(weight) (caustic_map.h), at
/// least one each.
std::vector<long long> share(long long total, const std::vector<double>& weight) {
  double sum = 0;
  for (double w : weight) sum += std::sqrt(w);
  std::vector<long long> n;
  for (double w : weight)
    n.push_back(std::max(1LL, std::llround(double(total) * std::sqrt(w) / sum)));
  return n;
}

/// The cones' photon budgets (share: sqrt of each cone's power), first photon indices, flux
/// scales and starting media, and each target's automatic gather radius (the smallest over its
/// cones; the settings' radius where given) in `radius`.
std::vector<ConePlan> plan_cones(const std::vector<LightCone>& cones,
                                 const std::vector<Emitter>& lights, const PhotonTracer& tracer,
                                 const CausticSettings& settings, std::vector<double>& radius) {
  std::vector<double> weight;
  for (const LightCone& c : cones) {
    const Emitter& l = lights[c.emitter];
    weight.push_back(luminance(l.intensity) * c.solid_angle_sr *
                     (l.inverse_square ? 1.0 : c.distance * c.distance));
  }
  const std::vector<long long> counts = share(settings.photons.value_or(kDefaultPhotons), weight);
  std::vector<ConePlan> plans;
  long long next = 0;
  for (std::size_t k = 0; k < cones.size(); ++k) {
    ConePlan p;
    p.cone = cones[k];
    p.count = counts[k];
    p.first = next;
    next += p.count;
    const Emitter& l = lights[p.cone.emitter];
    p.scale = p.cone.solid_angle_sr / double(p.count) *
              (l.inverse_square ? 1.0 : p.cone.distance * p.cone.distance);
    p.medium = tracer.medium_at(l.position);
    plans.push_back(p);
    // N_k photons cover the aimed-at sphere's cross-section pi R_k^2 where unfocused, so a disc
    // of radius R_k sqrt(K / N_k) holds K of them.
    const double r = p.cone.cone_radius * std::sqrt(kPhotonsPerDisc / double(p.count));
    double& rt = radius[p.cone.target_index];
    rt = rt == 0 ? r : std::min(rt, r);
  }
  if (settings.radius)
    for (double& r : radius) r = *settings.radius;
  return plans;
}

/// One path event of a photon of power `power` aimed at `target`: stored on a diffuse surface,
/// or its flux booked where the path ended.
void record_event(const PathEvent& e, const Rgb& power, std::uint32_t target, ChunkResult& part) {
  const Rgb tinted = power * e.tint;  // RGB absorption (photon_tracer.h)
  const Flux f = flux_of(tinted, e.weight);
  switch (e.end) {
    case PathEnd::stored:
      part.photons.push_back(Photon{e.position, e.normal, tinted * e.weight});
      part.target.push_back(target);
      part.stored += f;
      break;
    case PathEnd::direct:
      part.direct += f;
      break;
    case PathEnd::escaped:
      part.escaped += f;
      break;
    case PathEnd::absorbed:
      part.absorbed += f;
      break;
    case PathEnd::stopped:
      part.stopped += f;
      break;
    case PathEnd::cut:
      part.cut += f;
      break;
    case PathEnd::roulette: {
      part.roulette += f;
      // One event per decision on weight w: +w (ended) or -(T - w) (survived), of
      // variance w (T - w) times the photon's power squared.
      const double w = e.weight > 0 ? e.weight : kRouletteWeight + e.weight;
      const double v = w * (kRouletteWeight - w);
      part.roulette_variance +=
          Flux{tinted.r * tinted.r * v, tinted.g * tinted.g * v, tinted.b * tinted.b * v};
      break;
    }
  }
}

/// What the photon pass shares between its chunks.
struct PhotonPass {
  const std::vector<ConePlan>& plans;
  const std::vector<Emitter>& lights;
  const std::vector<RgbIlluminantSpectrum>& spectra;
  bool spectral;
  const PhotonTracer& tracer;
  long long photons;
};

/// Photons [c kChunk, (c + 1) kChunk) of the pass: each emitted along its cone's low-discrepancy
/// direction (unless an earlier cone of the same light owns it), traced, its events recorded.
void trace_chunk(const PhotonPass& pass, long long c, PathEvents& events, ChunkResult& part) {
  const std::vector<ConePlan>& plans = pass.plans;
  const long long g0 = c * kChunk, g1 = std::min(pass.photons, g0 + kChunk);
  std::size_t k = 0;
  for (long long g = g0; g < g1; ++g) {
    while (g >= plans[k].first + plans[k].count) ++k;
    const ConePlan& plan = plans[k];
    const auto i = static_cast<std::uint64_t>(g - plan.first);
    const Vec3 dir =
        plan.cone.direction(ScrambledHalton::sample(i, 0), ScrambledHalton::sample(i, 1));
    // Directions of earlier cones of the same light belong to those cones.
    bool owned_elsewhere = false;
    for (std::size_t j = 0; j < k && !owned_elsewhere; ++j)
      owned_elsewhere = plans[j].cone.emitter == plan.cone.emitter && plans[j].cone.contains(dir);
    if (owned_elsewhere) continue;
    const Emitter& light = pass.lights[plan.cone.emitter];
    double lambda = media::kFraunhoferD_nm;
    Rgb power = light.intensity * static_cast<float>(plan.scale);
    if (pass.spectral)
      power = photon_colour(pass.spectra[plan.cone.emitter], i, lambda) * plan.normalise *
              static_cast<float>(plan.scale);
    ++part.traced;
    part.emitted += flux_of(power, 1.0);
    const Vec3 origin =
        emission_point(light, dir, ScrambledHalton::sample(i, 3), ScrambledHalton::sample(i, 4));
    part.rays += pass.tracer.trace(Ray{origin, dir}, plan.medium, lambda, events, i);
    for (const PathEvent& e : events) record_event(e, power, plan.cone.target_index, part);
  }
}

}  // namespace

CausticMap CausticMap::build(const Scene& scene, int threads, const std::atomic<bool>* cancel) {
  const auto start = std::chrono::steady_clock::now();
  CausticMap result;
  const CausticSettings& settings = scene.caustics();
  if (!settings.enabled) return result;
  const std::vector<BoundingSphere> targets = dielectric_targets(scene);
  const std::vector<Emitter> lights = emitters(scene);
  const std::vector<LightCone> cones = light_cones(lights, targets);
  if (cones.empty()) return result;

  const PhotonTracer tracer(scene, kRouletteWeight);
  // bench/render/ray_limit tells the photons' rays from the frame's (nothing when not recording).
  const RayStreamScope photon_rays(RayStream::photon);
  std::vector<double> radius(targets.size(), 0.0);
  std::vector<ConePlan> plans = plan_cones(cones, lights, tracer, settings, radius);
  const long long photons = plans.back().first + plans.back().count;

  const bool spectral = photons_carry_wavelengths(scene);
  std::vector<RgbIlluminantSpectrum> spectra;
  for (const Emitter& l : lights)
    spectra.emplace_back(LinearSrgb{l.intensity.r, l.intensity.g, l.intensity.b});
  if (spectral)
    for (ConePlan& p : plans) {
      const Rgb& colour = lights[p.cone.emitter].intensity;
      p.normalise = colour_normalisation(spectra[p.cone.emitter], colour, p.count);
    }

  const PhotonPass pass{plans, lights, spectra, spectral, tracer, photons};
  const long long chunks = (photons + kChunk - 1) / kChunk;
  std::vector<ChunkResult> parts(static_cast<std::size_t>(chunks));
  const int nthreads = threads > 0 ? threads : omp_get_max_threads();
  bool out_of_memory = false;
#pragma omp parallel num_threads(nthreads)
  {
    PathEvents events;
#pragma omp for schedule(dynamic, 1)
    for (long long c = 0; c < chunks; ++c) {
      // Ctrl-C / SIGTERM: skip the remaining chunks (the caller writes nothing, interrupt.h).
      if ((cancel && cancel->load(std::memory_order_relaxed)) || interrupt_requested()) continue;
      try {
        trace_chunk(pass, c, events, parts[static_cast<std::size_t>(c)]);
      } catch (const std::bad_alloc&) {
#pragma omp atomic write
        out_of_memory = true;
      }
    }
  }
  if (out_of_memory) throw std::bad_alloc();

  CausticStatistics& st = result.m_stats;
  std::vector<std::vector<Photon>> per_target(targets.size());
  st.targets.resize(targets.size());
  for (const ChunkResult& p : parts) {  // chunk order: independent of the thread count
    for (std::size_t i = 0; i < p.photons.size(); ++i)
      per_target[p.target[i]].push_back(p.photons[i]);
    st.photons_traced += p.traced;
    st.rays += p.rays;
    st.emitted += p.emitted;
    st.stored += p.stored;
    st.direct += p.direct;
    st.escaped += p.escaped;
    st.absorbed += p.absorbed;
    st.stopped += p.stopped;
    st.cut += p.cut;
    st.roulette += p.roulette;
    st.roulette_variance += p.roulette_variance;
  }
  for (const ConePlan& p : plans) st.targets[p.cone.target_index].photons_traced += p.count;
  for (std::size_t t = 0; t < targets.size(); ++t) {
    TargetStatistics& ts = st.targets[t];
    ts.center = targets[t].center;
    ts.bounding_radius = targets[t].radius;
    ts.photons_stored = per_target[t].size();
    ts.radius = radius[t];
    st.photons_stored += ts.photons_stored;
    // A target without cones (no light reaches it) keeps an empty map.
    result.m_maps.emplace_back(per_target[t], static_cast<float>(radius[t] > 0 ? radius[t] : 1.0),
                               kSmoothPhotons);
  }
  st.cones = static_cast<int>(cones.size());
  st.threads = nthreads;
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace thaw::render::photon
