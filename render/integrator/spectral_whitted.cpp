#include "render/integrator/spectral_whitted.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <vector>

#include "render/material/fresnel.h"
#include "render/math/rng.h"
#include "render/spectrum/colour.h"
#include "render/spectrum/rgb_uplift.h"

namespace thaw::render {

namespace {

LinearSrgb to_srgb(const Rgb& c) { return {c.r, c.g, c.b}; }

/// Largest throughput over the wavelengths still carried (after termination only the hero's
/// value enters the estimator): the pruning weight, as Rgb::max_component() in RGB mode.
float live_max(const SampledSpectrum& s, const SampledWavelengths& w) {
  return w.secondary_terminated() ? s[0] : s.max_component();
}

/// Re-expresses radiance estimated with `terminated` (hero only, pdf p(l0)/N) in the caller's
/// wavelengths `w` (all live, common pdf q = (1/N) sum_k p(l_k)): the film's average
/// (1/N) sum_i L_i cmf_i / pdf_i must give the hero-only estimate L_0 cmf_0 / p(l0), so element
/// 0 becomes L_0 * pdf_w(0) / pdf_terminated(0) and the others 0. Identity when `w` is already
/// terminated.
SampledSpectrum to_caller_wavelengths(const SampledSpectrum& l, const SampledWavelengths& terminated,
                                      const SampledWavelengths& w) {
  if (w.secondary_terminated()) return l;
  SampledSpectrum out;
  out[0] = l[0] * (w.pdf(0) / terminated.pdf(0));
  return out;
}

class SpectralTracer {
 public:
  explicit SpectralTracer(const Scene& scene)
      : m_scene(scene),
        m_max_depth(scene.settings().max_depth),
        m_min_weight(static_cast<float>(scene.settings().min_weight)),
        m_split(scene.settings().dispersion == ImageSettings::Dispersion::split),
        m_background(to_srgb(scene.background())),
        m_ambient(to_srgb(scene.ambient())) {
    for (const auto& l : scene.lights()) m_lights.emplace_back(to_srgb(l.radiance));
    for (const auto& m : scene.materials()) m_emission.emplace_back(to_srgb(m.emission));
    for (const auto& m : scene.media()) {
      m_dispersive.push_back(m.optics.is_dispersive());
      m_absorbs.push_back(m.optics.absorbs());
      m_ior_constant.push_back(m.optics.n_at(media::kFraunhoferD_nm));
    }
  }

  /// Radiance along `ray` (unit direction) at tree level `depth` with throughput `beta`,
  /// travelling in `medium`, at wavelengths `w`. `lane` >= 0: the ray belongs to that carried
  /// wavelength alone (after a split dispersive refraction; beta is zero elsewhere and the caller
  /// keeps only that element of the result), -1: to every live wavelength.
  SampledSpectrum trace(const Ray& ray, int depth, const SampledSpectrum& beta, std::uint32_t medium,
                        const SampledWavelengths& w, int lane = -1) {
    ++rays;
    Hit hit;
    const bool absorbs = m_absorbs[medium] != 0;
    if (!m_scene.intersect(ray, hit)) {
      SampledSpectrum bg = spectra(w).background;
      // Escaping inside an absorbing medium: an infinite path keeps nothing where alpha > 0
      // (a huge finite distance avoids 0 * inf where alpha = 0).
      if (absorbs) bg *= m_scene.media()[medium].optics.transmittance(1e30, w);
      return bg;
    }
    SampledSpectrum transmittance(1.0f);
    SampledSpectrum b = beta;
    if (absorbs) {
      // Beer-Lambert over this segment: |direction| = 1, so t is the distance (scene units = m).
      transmittance = m_scene.media()[medium].optics.transmittance(hit.t, w);
      b *= transmittance;
    }
    const SurfaceInteraction si = m_scene.interaction(ray, hit);
    const SceneObject& obj = m_scene.objects()[si.object];
    SampledSpectrum l;
    if (obj.dielectric) {
      l = dielectric(ray, si, obj, depth, b, medium, w, lane);
    } else {
      const Material& mat = m_scene.materials()[obj.material];
      switch (mat.kind) {
        case Material::Kind::emissive:
          l = spectra(w).emission[obj.material];
          break;
        case Material::Kind::metal:
          l = metal(ray, si, mat, depth, b, medium, w, lane);
          break;
        case Material::Kind::matte:
        case Material::Kind::phong:
          l = phong(ray, si, mat, depth, b, medium, w, lane);
          break;
      }
    }
    return absorbs ? l * transmittance : l;
  }

  std::uint64_t rays = 0, mismatches = 0;

  /// Set when some dispersive refraction was split into lanes (render_spectral then traces the
  /// camera sample's remaining wavelength packets). Before its first dispersive refraction a ray
  /// tree is the same for every wavelength, so this depends on the camera ray alone, never on
  /// the sampled wavelengths: refining where it is set keeps the estimator unbiased.
  bool split_seen = false;

 private:
  SampledSpectrum dielectric(const Ray& ray, const SurfaceInteraction& si, const SceneObject& obj, int depth,
                             const SampledSpectrum& beta, std::uint32_t medium, const SampledWavelengths& w,
                             int lane) {
    const Vec3& d = ray.direction;
    const bool entering = dot(d, si.ng) < 0.0f;
    const std::uint32_t from = entering ? obj.outside : obj.inside;
    const std::uint32_t to = entering ? obj.inside : obj.outside;
    if (medium != from) ++mismatches;
    const Vec3 ng = entering ? si.ng : -si.ng;
    Vec3 ns = entering ? si.ns : -si.ns;
    if (dot(ns, d) >= 0.0f) ns = ng;
    const float cos_i = -dot(d, ns);
    SampledSpectrum result;
    if (depth >= m_max_depth) return result;
    const bool dispersive = (m_dispersive[from] | m_dispersive[to]) != 0;
    // Relative index per carried wavelength (one number for a non-dispersive interface).
    SampledSpectrum r, n_from(1.0f), n_to(1.0f);
    float eta_hero;
    if (!dispersive) {
      eta_hero = static_cast<float>(m_ior_constant[to] / m_ior_constant[from]);
      r = SampledSpectrum(fresnel_dielectric(cos_i, eta_hero));
    } else {
      const PacketSpectra& ps = spectra(w);
      n_from = ps.n[from];
      n_to = ps.n[to];
      // A ray of one wavelength refracts with that wavelength's index; its tree's other elements
      // are discarded by the caller, so their reflectances need not be computed.
      const int k = lane >= 0 ? lane : 0;
      eta_hero = n_to[k] / n_from[k];
      if (lane >= 0) {
        r[lane] = fresnel_dielectric(cos_i, eta_hero);
      } else {
        for (int i = 0; i < kSpectrumSamples; ++i) r[i] = fresnel_dielectric(cos_i, n_to[i] / n_from[i]);
      }
    }
    // Reflected branch: every carried wavelength, each with its own Fresnel reflectance.
    if (!r.is_black() && live_max(beta * r, w) >= m_min_weight) {
      Vec3 dir = reflect(d, ns);
      if (dot(dir, ng) <= 0.0f) dir = reflect(d, ng);
      const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
      result += trace(next, depth + 1, beta * r, from, w, lane) * r;
    }
    const SampledSpectrum t = SampledSpectrum(1.0f) - r;
    if (dispersive && lane < 0 && m_split && !w.secondary_terminated()) {
      split_seen = true;
      // Split: each carried wavelength refracts its own way on its own ray (4 rays). Every
      // wavelength's radiance is then exact, so the film estimator keeps all four: no colour
      // noise beyond the wavelength sampling itself.
      for (int i = 0; i < kSpectrumSamples; ++i) {
        SampledSpectrum mask;
        mask[i] = t[i];
        const SampledSpectrum b = beta * mask;
        if (!(b[i] >= m_min_weight) || b[i] == 0.0f) continue;
        Vec3 dir;
        const float eta = n_to[i] / n_from[i];
        bool ok = refract(d, ns, eta, dir) && dot(dir, ng) < 0.0f;
        if (!ok) ok = refract(d, ng, eta, dir);
        if (!ok) continue;
        const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
        result += trace(next, depth + 1, b, to, w, i) * mask;
      }
      return result;
    }
    Vec3 dir;
    bool ok = refract(d, ns, eta_hero, dir) && dot(dir, ng) < 0.0f;
    if (!ok) ok = refract(d, ng, eta_hero, dir);
    if (!ok) return result;
    const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
    if (!dispersive || w.secondary_terminated() || lane >= 0) {
      if (live_max(beta * t, w) >= m_min_weight) result += trace(next, depth + 1, beta * t, to, w, lane) * t;
      return result;
    }
    // Dispersive refraction: the wavelengths part ways; follow the hero only (Wilkie et al.).
    SampledWavelengths hero = w;
    hero.terminate_secondary();
    if (beta[0] * t[0] >= m_min_weight) {
      const SampledSpectrum lt = trace(next, depth + 1, beta * t, to, hero) * t;
      result += to_caller_wavelengths(lt, hero, w);
    }
    return result;
  }

  SampledSpectrum metal(const Ray& ray, const SurfaceInteraction& si, const Material& mat, int depth,
                        const SampledSpectrum& beta, std::uint32_t medium, const SampledWavelengths& w,
                        int lane) {
    const SampledSpectrum tint = RgbReflectanceSpectrum(to_srgb(mat.texture.eval(si.p))).sample(w);
    const SampledSpectrum b = beta * tint;
    const float wmax = live_max(b, w);
    if (depth >= m_max_depth || wmax < m_min_weight || wmax == 0.0f) return {};
    const Vec3 ng = face_forward(si.ng, -ray.direction);
    Vec3 ns = face_forward(si.ns, ng);
    Vec3 dir = reflect(ray.direction, ns);
    if (dot(dir, ng) <= 0.0f) dir = reflect(ray.direction, ng);
    const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
    return tint * trace(next, depth + 1, b, medium, w, lane);
  }

  SampledSpectrum phong(const Ray& ray, const SurfaceInteraction& si, const Material& mat, int depth,
                        const SampledSpectrum& beta, std::uint32_t medium, const SampledWavelengths& w,
                        int lane) {
    const Vec3& d = ray.direction;
    const Vec3 ng = face_forward(si.ng, -d);
    const Vec3 ns = face_forward(si.ns, ng);
    const SampledSpectrum albedo = RgbReflectanceSpectrum(to_srgb(mat.texture.eval(si.p))).sample(w);
    const PacketSpectra& ps = spectra(w);
    SampledSpectrum result = albedo * ps.ambient * mat.ka;
    const auto& lights = m_scene.lights();
    for (std::size_t li_index = 0; li_index < lights.size(); ++li_index) {
      const PointLight& light = lights[li_index];
      const Vec3 to_light = light.position - si.p;
      const float dist2 = dot(to_light, to_light);
      if (!(dist2 > 0.0f)) continue;
      const Vec3 l = to_light / std::sqrt(dist2);
      if (dot(l, ng) <= 0.0f) continue;
      const float cos_l = dot(ns, l);
      if (cos_l <= 0.0f) continue;
      const Vec3 origin = offset_ray_origin(si.p, si.p_error, ng, l);
      const Ray shadow{origin, light.position - origin, 1.0f - 1e-4f};
      ++rays;
      if (m_scene.occluded(shadow)) continue;
      SampledSpectrum li = ps.lights[li_index];
      if (light.inverse_square) li *= 1.0f / dist2;
      result += albedo * li * (mat.kd * cos_l);
      if (mat.ks > 0.0f) {
        const float s = dot(reflect(-l, ns), -d);
        if (s > 0.0f) result += li * (mat.ks * std::pow(s, mat.shininess));
      }
    }
    if (mat.kind != Material::Kind::phong || depth >= m_max_depth) return result;
    if (mat.reflectance > 0.0f && live_max(beta, w) * mat.reflectance >= m_min_weight) {
      Vec3 dir = reflect(d, ns);
      if (dot(dir, ng) <= 0.0f) dir = reflect(d, ng);
      const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
      result += trace(next, depth + 1, beta * mat.reflectance, medium, w, lane) * mat.reflectance;
    }
    if (mat.transmittance > 0.0f && live_max(beta, w) * mat.transmittance >= m_min_weight) {
      // The classic model: a constant ior relative to the front side (not dispersive).
      const bool entering = dot(d, si.ng) < 0.0f;
      const float eta = entering ? mat.ior : 1.0f / mat.ior;
      Vec3 dir;
      if (refract(d, ns, eta, dir) && dot(dir, ng) < 0.0f) {
        const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
        result += trace(next, depth + 1, beta * mat.transmittance, medium, w, lane) * mat.transmittance;
      }
    }
    return result;
  }

  const Scene& m_scene;
  int m_max_depth;
  float m_min_weight;
  bool m_split;
  RgbIlluminantSpectrum m_background, m_ambient;
  std::vector<RgbIlluminantSpectrum> m_lights, m_emission;

  /// Everything that depends on the wavelengths alone, evaluated once per wavelength packet
  /// (every ray of a camera sample's tree carries the same wavelengths; only their pdfs change
  /// after termination) instead of at every hit: the Sellmeier sums and the illuminant uplifts
  /// were a fifth of a dispersive render's time.
  struct PacketSpectra {
    SampledSpectrum lambda_nm{-1.0f};
    SampledSpectrum background, ambient;
    std::vector<SampledSpectrum> lights, emission, n;
  };
  PacketSpectra m_packet;

  const PacketSpectra& spectra(const SampledWavelengths& w) {
    const SampledSpectrum& l = w.lambdas_nm();
    bool same = true;
    for (int i = 0; i < kSpectrumSamples; ++i) same = same && l[i] == m_packet.lambda_nm[i];
    if (same) return m_packet;
    m_packet.lambda_nm = l;
    m_packet.background = m_background.sample(w);
    m_packet.ambient = m_ambient.sample(w);
    m_packet.lights.resize(m_lights.size());
    for (std::size_t i = 0; i < m_lights.size(); ++i) m_packet.lights[i] = m_lights[i].sample(w);
    m_packet.emission.resize(m_emission.size());
    for (std::size_t i = 0; i < m_emission.size(); ++i) m_packet.emission[i] = m_emission[i].sample(w);
    m_packet.n.resize(m_scene.media().size());
    for (std::size_t i = 0; i < m_packet.n.size(); ++i)
      m_packet.n[i] = m_dispersive[i] ? m_scene.media()[i].optics.n(w)
                                       : SampledSpectrum(static_cast<float>(m_ior_constant[i]));
    return m_packet;
  }
  std::vector<char> m_dispersive, m_absorbs;
  std::vector<double> m_ior_constant;
};

}  // namespace

bool spectral_refraction(const Vec3& d, const Vec3& n, double n_from, double n_to, Vec3& out) {
  return refract(d, n, static_cast<float>(static_cast<float>(n_to) / static_cast<float>(n_from)), out);
}

SampledSpectrum trace_spectral_ray(const Scene& scene, const Ray& ray, std::uint32_t medium,
                                   const SampledWavelengths& wavelengths, RenderStats* stats) {
  SpectralTracer tracer(scene);
  const SampledSpectrum l = tracer.trace(ray, 1, SampledSpectrum(1.0f), medium, wavelengths);
  if (stats) {
    stats->rays += tracer.rays;
    stats->medium_mismatches += tracer.mismatches;
  }
  return l;
}

RenderResult render_spectral(const Scene& scene, const RenderOptions& options, const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  const ImageSettings& st = scene.settings();
  const int w = st.width, h = st.height, spp = st.samples_per_pixel;
  const int tile = std::max(1, options.tile_size);
  const int tiles_x = (w + tile - 1) / tile, tiles_y = (h + tile - 1) / tile;
  const int tiles = tiles_x * tiles_y;
  RenderResult result;
  result.image = Image(w, h);
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  // Pixel positions stratified as in RGB mode; the hero wavelength gets its own spp strata in a
  // random order per pixel, so position and wavelength strata are not correlated.
  const int grid = static_cast<int>(std::lround(std::sqrt(double(spp))));
  const bool square = grid * grid == spp;
  // Ratio film: white's exact XYZ under the film's own estimator (midpoint quadrature over the
  // hero, 4000 cells: D65 and the CIE functions are smooth, error < 1e-6).
  const bool ratio = st.spectral_film == ImageSettings::SpectralFilm::ratio;
  Xyz white;
  if (ratio) {
    constexpr int kCells = 4000;
    for (int i = 0; i < kCells; ++i) {
      const auto wl = SampledWavelengths::sample((i + 0.5) / kCells);
      const Xyz c = spectrum_to_xyz(illuminant_d65(wl), wl);
      white.x += c.x / kCells, white.y += c.y / kCells, white.z += c.z / kCells;
    }
  }
  // Wavelength packets of kSpectrumSamples per camera sample where dispersion splits the rays.
  const int packets = st.dispersion == ImageSettings::Dispersion::split
                          ? std::max(1, st.dispersion_wavelengths / kSpectrumSamples)
                          : 1;
  // Shared wavelength pattern: one sub-stratum and one offset for the whole image, from the seed.
  const bool pattern_shared = st.wavelength_pattern == ImageSettings::WavelengthPattern::shared;
  Pcg32 pattern_rng(0x7468617770617474ULL, options.seed);  // stream "thawpatt"
  const int shared_first = int(pattern_rng.next_u32() % std::uint32_t(packets));
  const double shared_jitter = pattern_rng.next_float();
  std::uint64_t rays = 0, mismatches = 0, refined = 0;
  std::atomic<std::int64_t> tiles_done{0};
#pragma omp parallel num_threads(threads) reduction(+ : rays, mismatches, refined)
  {
    SpectralTracer tracer(scene);
    std::vector<int> perm(static_cast<std::size_t>(spp)), lambda_perm(static_cast<std::size_t>(spp));
    auto shuffle = [](std::vector<int>& p, Pcg32& rng) {
      for (std::size_t i = 0; i < p.size(); ++i) p[i] = static_cast<int>(i);
      for (std::size_t i = p.size() - 1; i > 0; --i)
        std::swap(p[i], p[rng.next_u32() % static_cast<std::uint32_t>(i + 1)]);
    };
#pragma omp for schedule(dynamic, 1)
    for (int t = 0; t < tiles; ++t) {
      const int x0 = (t % tiles_x) * tile, y0 = (t / tiles_x) * tile;
      const int x1 = std::min(x0 + tile, w), y1 = std::min(y0 + tile, h);
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
          Pcg32 rng(std::uint64_t(y) * std::uint64_t(w) + std::uint64_t(x), options.seed);
          if (!square && spp > 1) shuffle(perm, rng);
          shuffle(lambda_perm, rng);
          Xyz sum, white_sum;
          for (int s = 0; s < spp; ++s) {
            float sx = 0.5f, sy = 0.5f;  // one sample: the pixel centre (as RGB mode and POV-Ray)
            if (spp > 1 && square) {
              sx = (float(s % grid) + rng.next_float()) / float(grid);
              sy = (float(s / grid) + rng.next_float()) / float(grid);
            } else if (spp > 1) {
              sx = (float(s) + rng.next_float()) / float(spp);
              sy = (float(perm[static_cast<std::size_t>(s)]) + rng.next_float()) / float(spp);
            }
            // Wavelength packets: the first always, all of them when the first met a split
            // dispersive refraction. Packet k takes sub-stratum (first + k) mod packets of the
            // sample's hero stratum, at offset `jitter` in it. Per pixel, `first` and `jitter` are
            // random for each sample; shared, they are the same for every pixel (drawn once from
            // the seed): each is uniform, so an unrefined sample's hero is uniform in its stratum
            // and a refined sample's heroes are stratified, in both patterns.
            const int first = pattern_shared ? shared_first : packets > 1 ? int(rng.next_u32() % std::uint32_t(packets)) : 0;
            const Ray camera_ray = scene.camera().generate(float(x) + sx, float(y) + sy);
            Xyz sample_sum, sample_white;
            int traced = 0;
            for (int k = 0; k < packets; ++k) {
              const double jitter = pattern_shared ? shared_jitter : double(rng.next_float());
              const double sub = (double((first + k) % packets) + jitter) / double(packets);
              const double u = (double(lambda_perm[static_cast<std::size_t>(s)]) + sub) / double(spp);
              const SampledWavelengths wl = SampledWavelengths::sample(std::min(u, 1.0 - 1e-12));
              tracer.split_seen = false;
              const SampledSpectrum l =
                  tracer.trace(camera_ray, 1, SampledSpectrum(1.0f), scene.camera_medium(), wl);
              // Box filter: the mean of the samples' XYZ. Negative sRGB (out-of-gamut spectral
              // colours) is kept and clamped at output, so the mean stays unbiased.
              const Xyz c = spectrum_to_xyz(l, wl);
              sample_sum.x += c.x, sample_sum.y += c.y, sample_sum.z += c.z;
              if (ratio) {
                const Xyz d = spectrum_to_xyz(illuminant_d65(wl), wl);
                sample_white.x += d.x, sample_white.y += d.y, sample_white.z += d.z;
              }
              ++traced;
              if (k == 0 && !tracer.split_seen) break;
            }
            if (traced > 1) ++refined;
            sum.x += sample_sum.x / traced, sum.y += sample_sum.y / traced, sum.z += sample_sum.z / traced;
            white_sum.x += sample_white.x / traced, white_sum.y += sample_white.y / traced;
            white_sum.z += sample_white.z / traced;
          }
          Xyz mean{sum.x / spp, sum.y / spp, sum.z / spp};
          if (ratio) {
            // white_sum > 0: D65 and the CIE functions are positive over 380-780 nm.
            mean = Xyz{sum.x / white_sum.x * white.x, sum.y / white_sum.y * white.y,
                       sum.z / white_sum.z * white.z};
          }
          const LinearSrgb c = xyz_to_linear_srgb(mean);
          result.image.at(x, y) = Rgb(float(c.r), float(c.g), float(c.b));
        }
      }
      const std::int64_t done = ++tiles_done;
      if (progress) {
        try {
          progress(done, tiles);
        } catch (...) {
          // A progress display must never abort a render (and nothing may leave an OpenMP loop).
        }
      }
    }
    rays += tracer.rays;
    mismatches += tracer.mismatches;
  }
  result.stats.rays = rays;
  result.stats.medium_mismatches = mismatches;
  result.stats.refined_samples = refined;
  result.stats.threads = threads;
  result.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.stats.rays_per_second = result.stats.seconds > 0 ? double(rays) / result.stats.seconds : 0.0;
  return result;
}

}  // namespace thaw::render
