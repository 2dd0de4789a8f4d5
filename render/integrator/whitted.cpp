#include "render/integrator/whitted.h"

#include <cmath>

#include "render/integrator/image_tile_integrator.h"
#include "render/integrator/spectral_whitted.h"
#include "render/integrator/whitted_shading.h"

namespace thaw::render {

namespace {

/// The RGB variant of the shading: radiance as linear sRGB triples, a scalar pruning weight,
/// media indices at the sodium D line (589.3 nm), Beer-Lambert absorption with one coefficient
/// per channel (media::Absorption::srgb_per_m: white light's channel-weighted alpha, exact to
/// first order in alpha d), no dispersion.
class RgbTracer : public WhittedShading<RgbTracer> {
 public:
  using Radiance = Rgb;
  using Throughput = float;
  using Reflectance = float;
  struct Path {};
  static constexpr bool kAbsorption = true, kDispersion = false;

  explicit RgbTracer(const Scene& scene, const photon::CausticMap* caustics = nullptr)
      : WhittedShading(scene, caustics) {
    for (const auto& m : scene.media()) {
      m_ior.push_back(static_cast<float>(m.optics.n_at(media::kFraunhoferD_nm)));
      const LinearSrgb a = m.optics.absorption().srgb_per_m();
      m_alpha.push_back(Rgb{float(a.r), float(a.g), float(a.b)});
    }
  }

  /// Radiance of a primary ray starting in `medium`; `camera`: the camera sample it belongs to
  /// (light samples), null outside a render.
  Rgb trace_primary(const Ray& ray, std::uint32_t medium,
                    const CameraSampleContext* camera = nullptr) {
    set_camera_sample(camera);
    return trace(ray, 1, 1.0f, medium, Path{});
  }

 private:
  friend class WhittedShading<RgbTracer>;
  struct Fresnel {
    float r, eta;
    bool dispersive;
  };

  static Rgb illuminant(const Rgb& c, const Path&) { return c; }
  static Rgb reflectance(const Rgb& c, const Path&) { return c; }
  Rgb light_radiance(std::size_t i, const Path&) const { return m_scene.lights()[i].radiance; }
  Rgb ambient(const Path&) const { return m_scene.ambient(); }
  Rgb emission(std::uint32_t material, const Path&) const {
    return m_scene.materials()[material].emission;
  }
  static float weight(float beta, const Path&) { return beta; }
  /// A scalar weight: the tint's largest component (POV-Ray's adaptive depth control).
  static float attenuate(float beta, const Rgb& tint, const Path&) {
    return beta * tint.max_component();
  }
  bool absorbs(std::uint32_t medium) const { return !m_alpha[medium].is_black(); }
  /// exp(-alpha_c d) per channel; d [m] (scene units are metres).
  Rgb transmittance(std::uint32_t medium, double distance, const Path&) const {
    const Rgb& a = m_alpha[medium];
    return {float(std::exp(-double(a.r) * distance)), float(std::exp(-double(a.g) * distance)),
            float(std::exp(-double(a.b) * distance))};
  }
  Fresnel fresnel(std::uint32_t from, std::uint32_t to, float cos_i, const Path&) const {
    const float eta = m_ior[to] / m_ior[from];
    return {fresnel_dielectric(cos_i, eta), eta, false};
  }

  std::vector<float> m_ior;
  std::vector<Rgb> m_alpha;  ///< per medium, [1/m]
};

/// One thread's share of an RGB render: each camera sample's radiance; the film
/// (image_tile_integrator.h) weighs and averages them.
class RgbPixelWorker {
 public:
  using Sample = Rgb;
  RgbPixelWorker(const Scene& scene, const photon::CausticMap* caustics)
      : m_tracer(scene, caustics), m_medium(scene.camera_medium()) {}
  void start_pixel(Pcg32&) {}
  Rgb sample(const Ray& camera_ray, const CameraSampleContext& camera, Pcg32&) {
    return m_tracer.trace_primary(camera_ray, m_medium, &camera);
  }
  static Rgb pixel_value(const Rgb& sum, int samples) { return sum * (1.0f / float(samples)); }
  void add_counts(RenderStats& stats) const { m_tracer.add_counts(stats); }

 private:
  RgbTracer m_tracer;
  std::uint32_t m_medium;
};

}  // namespace

Rgb trace_ray(const Scene& scene, const Ray& ray, std::uint32_t medium, RenderStats* stats) {
  RgbTracer tracer(scene);
  const Rgb c = tracer.trace_primary(ray, medium);
  if (stats) tracer.add_counts(*stats);
  return c;
}

RenderResult render(const Scene& scene, const RenderOptions& options,
                    const ProgressCallback& progress) {
  // The photon pass first (empty when [caustics] enabled = false or nothing can focus light).
  const photon::CausticMap caustics =
      photon::CausticMap::build(scene, options.threads, options.cancel);
  RenderResult result = scene.spectral() ? render_spectral(scene, options, progress, &caustics)
                                         : render_image_tiles(scene, options, progress, [&] {
                                             return RgbPixelWorker(scene, &caustics);
                                           });
  const photon::CausticStatistics& cs = caustics.statistics();
  result.stats.caustic_photons = cs.photons_traced;
  result.stats.caustic_photons_stored = cs.photons_stored;
  result.stats.caustic_seconds = cs.seconds;
  return result;
}

}  // namespace thaw::render
