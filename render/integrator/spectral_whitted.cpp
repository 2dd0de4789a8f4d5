#include "render/integrator/spectral_whitted.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "base/fnv_hash.h"
#include "render/integrator/image_tile_integrator.h"
#include "render/integrator/whitted_shading.h"
#include "render/material/fresnel.h"
#include "render/math/rng.h"
#include "render/spectrum/colour.h"
#include "render/spectrum/rgb_uplift.h"

namespace thaw::render {

namespace {

LinearSrgb to_srgb(const Rgb& c) {
  return {c.r, c.g, c.b};
}

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
SampledSpectrum to_caller_wavelengths(const SampledSpectrum& l,
                                      const SampledWavelengths& terminated,
                                      const SampledWavelengths& w) {
  if (w.secondary_terminated()) return l;
  SampledSpectrum out;
  out[0] = l[0] * (w.pdf(0) / terminated.pdf(0));
  return out;
}

/// int_a^b D65(l) cmf(l) dl (D65 with unit luminance, as illuminant_d65), from prefix sums on a
/// 0.25 nm grid (midpoint rule on functions piecewise linear at 5 nm: error < 1e-7 relative).
Xyz d65_xyz_integral(double a_nm, double b_nm) {
  constexpr double kStep = 0.25;
  constexpr int kCells = static_cast<int>((kLambdaMaxNm - kLambdaMinNm) / kStep);
  static const std::vector<Xyz> prefix = [] {
    std::vector<Xyz> p(kCells + 1);
    for (int i = 0; i < kCells; ++i) {
      const double l = kLambdaMinNm + (i + 0.5) * kStep;
      const Xyz bar = cie_xyz_bar(l);
      const double e = illuminant_d65(l) * kStep;
      p[i + 1] = Xyz{p[i].x + e * bar.x, p[i].y + e * bar.y, p[i].z + e * bar.z};
    }
    return p;
  }();
  auto at = [&](double l) {
    const double x = std::clamp((l - kLambdaMinNm) / kStep, 0.0, double(kCells));
    const int i = std::min(static_cast<int>(x), kCells - 1);
    const double t = x - i;
    return Xyz{prefix[i].x + t * (prefix[i + 1].x - prefix[i].x),
               prefix[i].y + t * (prefix[i + 1].y - prefix[i].y),
               prefix[i].z + t * (prefix[i + 1].z - prefix[i].z)};
  };
  const Xyz hi = at(b_nm), lo = at(a_nm);
  return {hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
}

/// The spectral shape a segment of adaptive dispersion is expected to have: D65 times the Smits
/// uplift of the colour its light ends on (normalised to a maximum of 1; white if black), so
/// a matte surface under white light seen through the glass is integrated exactly.
class ReferenceSpectrum {
 public:
  explicit ReferenceSpectrum(const Rgb& c)
      : m_grey(c.r == c.g && c.g == c.b), m_shape(normalised(c)) {}
  /// shape at l (the factor multiplying D65)
  double operator()(double l) const { return m_shape(l); }
  /// int_a^b D65 shape cmf dl: the shape is constant on Smits' 10 nm bins, so exact from the
  /// D65 prefix sums.
  Xyz xyz_integral(double a, double b) const {
    if (m_grey) return d65_xyz_integral(a, b);  // the white basis is 1 everywhere
    Xyz out;
    for_each_bin(a, b, [&](double lo, double hi) {
      const double v = m_shape(0.5 * (lo + hi));
      const Xyz part = d65_xyz_integral(lo, hi);
      out.x += v * part.x, out.y += v * part.y, out.z += v * part.z;
    });
    return out;
  }
  /// Middle of the 10 nm bin within [a, b] where D65 x shape x y-bar is largest.
  double brightest_nm(double a, double b) const {
    double best = 0.5 * (a + b), best_value = -1;
    for_each_bin(a, b, [&](double lo, double hi) {
      const double l = 0.5 * (lo + hi);
      const double v = m_shape(l) * illuminant_d65(l) * (cie_xyz_bar(l).y + 1e-3);
      if (v > best_value) best_value = v, best = l;
    });
    return best;
  }

 private:
  /// fn(lo, hi) for each part of [a, b] within one of Smits' 10 nm bins.
  template <class Fn>
  static void for_each_bin(double a, double b, Fn&& fn) {
    for (int k = 0; k < smits::kBins; ++k) {
      const double lo = std::max(a, smits::kBinStartNm + k * smits::kBinWidthNm);
      const double hi = std::min(b, smits::kBinStartNm + (k + 1) * smits::kBinWidthNm);
      if (hi > lo) fn(lo, hi);
    }
  }
  static LinearSrgb normalised(const Rgb& c) {
    const double m = std::max({double(c.r), double(c.g), double(c.b)});
    if (!(m > 0) || !std::isfinite(m)) return {1, 1, 1};
    return {c.r / m, c.g / m, c.b / m};
  }
  bool m_grey;
  RgbReflectanceSpectrum m_shape;
};

/// What rides along a spectral ray: the packet's wavelengths and, after a split dispersive
/// refraction, the one carried wavelength (lane) it belongs to.
struct SpectralPath {
  const SampledWavelengths* w;
  /// >= 0: the ray belongs to that carried wavelength alone (beta is zero elsewhere and the
  /// caller keeps only that element of the result); -1: to every live wavelength
  int lane = -1;
};

/// What one camera sample's packet of wavelengths gave.
struct PacketResult {
  SampledSpectrum radiance;
  /// light integrated over the spectrum at adaptive dispersive refractions (film adds it after
  /// the ratio normalisation: it carries no wavelength-sampling noise)
  Xyz side_xyz;
  /// some dispersive refraction was split into lanes (the film then traces the camera sample's
  /// remaining wavelength packets). Before its first dispersive refraction a ray tree is the
  /// same for every wavelength, so this depends on the camera ray alone, never on the sampled
  /// wavelengths: refining where it is set keeps the estimator unbiased.
  bool split_seen = false;
};

/// The spectral variant of the shading (whitted_shading.h) plus what only spectra have:
/// wavelength-dependent indices, Beer-Lambert absorption, and the three ways through a
/// dispersive refraction (split, adaptive, hero). Every ray it traces, also inside the adaptive
/// machinery, goes through the shared trace().
class SpectralTracer : public WhittedShading<SpectralTracer> {
 public:
  using Radiance = SampledSpectrum;
  using Throughput = SampledSpectrum;
  using Reflectance = SampledSpectrum;
  using Path = SpectralPath;
  static constexpr bool kAbsorption = true, kDispersion = true;

  explicit SpectralTracer(const Scene& scene, const photon::CausticMap* caustics = nullptr)
      : WhittedShading(scene, caustics),
        m_resolution_nm(scene.settings().dispersion_resolution_nm),
        m_split(scene.settings().dispersion != ImageSettings::Dispersion::hero),
        m_adaptive(scene.settings().dispersion == ImageSettings::Dispersion::adaptive),
        m_background_rgb(scene.background()),
        m_background(to_srgb(scene.background())),
        m_ambient(to_srgb(scene.ambient())) {
    for (const auto& l : scene.lights()) m_lights.emplace_back(to_srgb(l.radiance));
    for (const auto& m : scene.materials()) m_emission.emplace_back(to_srgb(m.emission));
    for (const auto& m : scene.media()) {
      m_dispersive.push_back(m.optics.is_dispersive());
      m_absorbs.push_back(m.optics.absorbs());
      m_any_absorbs = m_any_absorbs || m.optics.absorbs();
      m_ior_constant.push_back(m.optics.n_at(media::kFraunhoferD_nm));
    }
    set_probe_grid(scene.settings().dispersion_wavelengths);
  }

  /// Traces a primary ray starting in `medium` at wavelengths `w`; `camera`: the camera sample it
  /// belongs to (light samples), null outside a render.
  PacketResult trace_primary(const Ray& ray, std::uint32_t medium, const SampledWavelengths& w,
                             const CameraSampleContext* camera = nullptr) {
    set_camera_sample(camera);
    m_split_seen = false;
    m_side_xyz = Xyz{};
    PacketResult r;
    r.radiance = trace(ray, 1, SampledSpectrum(1.0f), medium, SpectralPath{&w, -1});
    r.side_xyz = m_side_xyz;
    r.split_seen = m_split_seen;
    return r;
  }

  /// Adds rays, mismatches and the dispersive refractions integrated adaptively / split.
  void add_counts(RenderStats& stats) const {
    WhittedShading::add_counts(stats);
    stats.adaptive_refractions += m_adaptive_refractions;
    stats.split_refractions += m_split_refractions;
  }

 private:
  friend class WhittedShading<SpectralTracer>;

  // ---- The shading's hooks (whitted_shading.h) ----
  SampledSpectrum illuminant(const Rgb& c, const Path& path) {
    // The scene's background is uplifted once per packet; any other colour (an environment) here.
    if (c.r == m_background_rgb.r && c.g == m_background_rgb.g && c.b == m_background_rgb.b)
      return spectra(*path.w).background;
    return RgbIlluminantSpectrum(to_srgb(c)).sample(*path.w);
  }
  static SampledSpectrum reflectance(const Rgb& c, const Path& path) {
    return RgbReflectanceSpectrum(to_srgb(c)).sample(*path.w);
  }
  SampledSpectrum light_radiance(std::size_t i, const Path& path) {
    return spectra(*path.w).lights[i];
  }
  SampledSpectrum ambient(const Path& path) { return spectra(*path.w).ambient; }
  SampledSpectrum emission(std::uint32_t material, const Path& path) {
    return spectra(*path.w).emission[material];
  }
  static float weight(const SampledSpectrum& beta, const Path& path) {
    return live_max(beta, *path.w);
  }
  static SampledSpectrum attenuate(const SampledSpectrum& beta, const SampledSpectrum& tint,
                                   const Path&) {
    return beta * tint;
  }
  bool absorbs(std::uint32_t medium) const { return m_absorbs[medium] != 0; }
  SampledSpectrum transmittance(std::uint32_t medium, double distance, const Path& path) const {
    return m_scene.media()[medium].optics.transmittance(distance, *path.w);
  }

  struct Fresnel {
    SampledSpectrum r;
    /// relative index of the ray's single direction (the hero's or the lane's wavelength)
    float eta;
    /// the carried wavelengths part ways here: dispersive_transmission() takes over
    bool dispersive;
  };
  Fresnel fresnel(std::uint32_t from, std::uint32_t to, float cos_i, const Path& path) {
    Fresnel f{};
    if ((m_dispersive[from] | m_dispersive[to]) == 0) {
      f.eta = static_cast<float>(m_ior_constant[to] / m_ior_constant[from]);
      f.r = SampledSpectrum(fresnel_dielectric(cos_i, f.eta));
      return f;
    }
    const PacketSpectra& ps = spectra(*path.w);
    // A ray of one wavelength refracts with that wavelength's index; its tree's other elements
    // are discarded by the caller, so their reflectances need not be computed.
    const int k = path.lane >= 0 ? path.lane : 0;
    f.eta = ps.n[to][k] / ps.n[from][k];
    if (path.lane >= 0) {
      f.r[path.lane] = fresnel_dielectric(cos_i, f.eta);
    } else {
      for (int i = 0; i < kSpectrumSamples; ++i)
        f.r[i] = fresnel_dielectric(cos_i, ps.n[to][i] / ps.n[from][i]);
    }
    f.dispersive = path.lane < 0 && !path.w->secondary_terminated();
    return f;
  }

  /// The transmitted branch of a dispersive refraction carrying several live wavelengths
  /// (transmittance t per wavelength): integrated adaptively, split into one ray per wavelength,
  /// or followed for the hero only ([image] dispersion).
  void dispersive_transmission(SampledSpectrum& result, const Vec3& d, const SurfaceInteraction& si,
                               const FacingInterface& fi, float cos_i, int depth,
                               const SampledSpectrum& beta, const SampledSpectrum& t,
                               const Path& path) {
    const SampledWavelengths& w = *path.w;
    const auto [from, to, ng, ns] = fi;
    if (m_split) {
      m_split_seen = true;
      if (m_adaptive && !m_any_absorbs && is_grey(beta)) {
        // Upstream throughput independent of the wavelength: integrate the transmitted light
        // over the whole spectrum here (its XYZ goes to side_xyz).
        ++m_adaptive_refractions;
        adaptive_transmission(d, si, ns, ng, cos_i, from, to, depth, beta[0], w);
        return;
      }
      ++m_split_refractions;
      // Split: each carried wavelength refracts its own way on its own ray (4 rays). Every
      // wavelength's radiance is then exact, so the film estimator keeps all four: no colour
      // noise beyond the wavelength sampling itself.
      const PacketSpectra& ps = spectra(w);
      for (int i = 0; i < kSpectrumSamples; ++i) {
        SampledSpectrum mask;
        mask[i] = t[i];
        const SampledSpectrum b = beta * mask;
        if (!(b[i] >= m_min_weight) || b[i] == 0.0f) continue;
        Vec3 dir;
        if (!refraction_direction(d, ns, ng, ps.n[to][i] / ps.n[from][i], dir)) continue;
        const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
        result += trace(next, depth + 1, b, to, SpectralPath{&w, i}) * mask;
      }
      return;
    }
    // Hero: the wavelengths part ways; follow the hero only (Wilkie et al.).
    Vec3 dir;
    if (!refraction_direction(d, ns, ng, spectra(w).n[to][0] / spectra(w).n[from][0], dir)) return;
    const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
    SampledWavelengths hero = w;
    hero.terminate_secondary();
    if (beta[0] * t[0] >= m_min_weight) {
      const SampledSpectrum lt = trace(next, depth + 1, beta * t, to, SpectralPath{&hero, -1}) * t;
      result += to_caller_wavelengths(lt, hero, w);
    }
  }

  // ---- Adaptive dispersion ----

  /// Where the main chain of one wavelength ends (see chain_end()).
  struct ChainEnd {
    std::uint64_t hash = 0;        // objects met, total reflections, end colour (not the lights)
    Rgb colour{1.0f, 1.0f, 1.0f};  // colour it ends on: reference spectrum of its segment
    bool lit = false;              // ends on a diffuse surface, whose light visibility matters
    Vec3 p, p_error, g, s;         // that surface point, its error bound, normals facing the chain
  };
  struct SpectralNode {
    double lambda_nm;
    ChainEnd end;
    std::uint64_t signature;  // end.hash and the lights it sees (set once probed)
    double f;  // transmitted radiance t(l) L(l) at this wavelength; valid where traced
    bool traced;
  };

  std::vector<SpectralNode> m_nodes;
  std::vector<double> m_grid_nm;  // probe wavelengths, ascending (set_probe_grid)

  /// Probe grid of adaptive dispersion ([image] dispersion_wavelengths): `count` intervals over
  /// 380-780 nm, in equal steps of the CDF of (x + y + z)(l) D65(l) / its peak + 0.2: densest where
  /// a misplaced colour jump costs most (the violet-blue and the orange-red fringes both; on S3
  /// this placement gave 11 % less colour error than the eye-sensitivity density at the same cost),
  /// never sparse.
  void set_probe_grid(int count) {
    const int probe_count = std::max(1, count);
    static const std::vector<double> cdf = [] {
      constexpr int kSteps = 400;  // 1 nm
      std::vector<double> c(kSteps + 1, 0.0);
      double peak = 0;
      for (int i = 0; i < kSteps; ++i) {
        const Xyz bar = cie_xyz_bar(kLambdaMinNm + i + 0.5);
        peak = std::max(peak, (bar.x + bar.y + bar.z) * illuminant_d65(kLambdaMinNm + i + 0.5));
      }
      for (int i = 0; i < kSteps; ++i) {
        const double l = kLambdaMinNm + i + 0.5;
        const Xyz bar = cie_xyz_bar(l);
        c[i + 1] = c[i] + (bar.x + bar.y + bar.z) * illuminant_d65(l) / peak + 0.2;
      }
      for (double& v : c) v /= c[kSteps];
      return c;
    }();
    m_grid_nm.assign(static_cast<std::size_t>(probe_count) + 1, 0.0);
    for (int g = 0; g <= probe_count; ++g) {
      const double u = double(g) / probe_count;
      const auto i =
          std::clamp<std::ptrdiff_t>(std::lower_bound(cdf.begin(), cdf.end(), u) - cdf.begin(), 1,
                                     std::ptrdiff_t(cdf.size()) - 1);
      const double t = (u - cdf[i - 1]) / (cdf[i] - cdf[i - 1]);
      m_grid_nm[static_cast<std::size_t>(g)] =
          kLambdaMinNm + double(i - 1) + std::clamp(t, 0.0, 1.0);
    }
    m_grid_nm.front() = kLambdaMinNm;
    m_grid_nm.back() = kLambdaMaxNm;
  }

  double index_at(std::uint32_t medium, double lambda_nm) const {
    return m_dispersive[medium] ? m_scene.media()[medium].optics.n_at(lambda_nm)
                                : m_ior_constant[medium];
  }

  static bool is_grey(const SampledSpectrum& s) {
    for (int i = 1; i < kSpectrumSamples; ++i)
      if (s[i] != s[0]) return false;
    return true;
  }

  static std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
    // FNV-1a's step over 64-bit words: order-sensitive, cheap; collisions only merge segments.
    return fnv1a_64_step(h, v);
  }
  static std::uint64_t bits(float v) {
    std::uint32_t u;
    std::memcpy(&u, &v, sizeof u);
    return u;
  }

  /// What the light of one wavelength refracted at a dispersive interface (incident direction d,
  /// normals facing the incident side) ends on, along its main chain: refraction through every
  /// further dielectric (reflection where that one is total), mirror reflection off metals, up to
  /// the first diffuse or emissive surface; hashed with the objects met and that surface's
  /// texture colour. With the lights that surface sees (full_signature) this is the wavelength's
  /// signature: two wavelengths with the same signature see the same colours through the same
  /// chain, so the transmitted radiance is smooth in the wavelength between them; where
  /// signatures differ the spectrum jumps (a fringe).
  ChainEnd chain_end(const Vec3& d, const SurfaceInteraction& at, const Vec3& ns, const Vec3& ng,
                     std::uint32_t from, std::uint32_t to, int depth, double lambda_nm) {
    constexpr std::uint64_t kTotalReflection = 0x9e3779b97f4a7c15ULL,
                            kEscaped = 0x632be59bd9b4e019ULL, kCut = 0x85ebca77c2b2ae63ULL;
    ChainEnd end;
    Vec3 dir;
    if (!refraction_direction(
            d, ns, ng, static_cast<float>(index_at(to, lambda_nm) / index_at(from, lambda_nm)),
            dir)) {
      end.hash = kTotalReflection;
      return end;
    }
    Ray ray{offset_ray_origin(at.p, at.p_error, ng, dir), dir};
    std::uint64_t h = kFnv1aOffset;
    for (int level = depth + 1; level <= m_max_depth; ++level) {
      ++m_rays;
      Hit hit;
      if (!m_scene.intersect(ray, hit)) {
        end.colour = m_scene.background();
        end.hash = mix(h, kEscaped);
        return end;
      }
      const SurfaceInteraction si = m_scene.interaction(ray, hit);
      const SceneObject& obj = m_scene.objects()[si.object];
      h = mix(h, si.object);
      const Vec3& rd = ray.direction;
      if (obj.dielectric) {
        const FacingInterface fi = facing_interface(rd, si, obj);
        Vec3 next;
        const float eta =
            static_cast<float>(index_at(fi.to, lambda_nm) / index_at(fi.from, lambda_nm));
        if (!refraction_direction(rd, fi.ns, fi.ng, eta, next)) {
          h = mix(h, kTotalReflection);
          next = reflection_direction(rd, fi.ns, fi.ng);
        }
        ray = Ray{offset_ray_origin(si.p, si.p_error, fi.ng, next), next};
        continue;
      }
      const Material& mat = m_scene.materials()[obj.material];
      const Vec3 g = face_forward(si.ng, -rd);
      const Vec3 s = face_forward(si.ns, g);
      if (mat.kind == Material::Kind::metal) {
        const Vec3 next = reflection_direction(rd, s, g);
        ray = Ray{offset_ray_origin(si.p, si.p_error, g, next), next};
        continue;
      }
      const Rgb c = mat.texture.eval(si.p);
      end.hash = mix(mix(mix(h, bits(c.r)), bits(c.g)), bits(c.b));
      end.colour = mat.kind == Material::Kind::emissive ? mat.emission : c;
      end.lit = mat.kind != Material::Kind::emissive;
      end.p = si.p, end.p_error = si.p_error, end.g = g, end.s = s;
      return end;
    }
    end.hash = mix(h, kCut);
    return end;
  }

  /// The signature of a chain end: its hash and, on a diffuse surface, the lights it sees
  /// (shadow rays, as add_direct_light() casts them).
  std::uint64_t full_signature(const ChainEnd& end) {
    if (!end.lit) return end.hash;
    std::uint64_t h = end.hash;
    const auto& lights = m_scene.lights();
    for (std::size_t i = 0; i < lights.size(); ++i) {
      Vec3 l;
      float cos_l, dist2;
      const LightVisibility v =
          light_visibility(end.p, end.p_error, end.g, end.s, lights[i], l, cos_l, dist2);
      if (v != LightVisibility::facing_away)
        h = mix(h, (std::uint64_t{i} << 1) | (v == LightVisibility::seen ? 1u : 0u));
    }
    return h;
  }

  /// t(l) L(l): the light of wavelength `lambda_nm` refracted at the interface, with upstream
  /// throughput `b`, traced as lane `lane` of the packet `w` (whose wavelength `lane` must be
  /// lambda_nm: the packet's spectra stay cached) or, lane < 0, of a packet of that wavelength.
  double transmitted_at(const Vec3& d, const SurfaceInteraction& si, const Vec3& ns, const Vec3& ng,
                        float cos_i, std::uint32_t from, std::uint32_t to, int depth, float b,
                        double lambda_nm, const SampledWavelengths& w, int lane) {
    const float eta = static_cast<float>(index_at(to, lambda_nm) / index_at(from, lambda_nm));
    const float t = 1.0f - fresnel_dielectric(cos_i, eta);
    if (!(b * t >= m_min_weight)) return 0.0;
    Vec3 dir;
    if (!refraction_direction(d, ns, ng, eta, dir)) return 0.0;
    const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
    SampledSpectrum beta;
    if (lane >= 0) {
      beta[lane] = b * t;
      return double(t) * double(trace(next, depth + 1, beta, to, SpectralPath{&w, lane})[lane]);
    }
    const SampledWavelengths single = SampledWavelengths::from(
        SampledSpectrum(static_cast<float>(lambda_nm)), SampledSpectrum(1.0f));
    beta[0] = b * t;
    return double(t) * double(trace(next, depth + 1, beta, to, SpectralPath{&single, 0})[0]);
  }

  /// Adaptive spectral integration of the transmitted light (dispersion = "adaptive"), for a
  /// split whose upstream throughput `b` is the same at every wavelength. The transmitted
  /// radiance f(l) = t(l) L(l) is smooth in l except where the refracted light starts to see
  /// something else (a checker edge, a silhouette, a shadow): the fringes. So:
  /// 1. signatures (chain_end() + full_signature()) on the probe grid (set_probe_grid(): 380
  ///    and 780 nm included) and at the packet's hero wavelength, whose f is traced (one lane);
  /// 2. wherever neighbouring signatures differ, bisection (signatures only: a few rays each)
  ///    locates each jump to within resolution_nm;
  /// 3. the range falls into segments of one signature each; a segment without a traced
  ///    wavelength gets one lane where its reference spectrum (below) is largest;
  /// 4. each segment's XYZ is the exact integral of its reference spectrum E = D65 x (Smits
  ///    uplift of the colour the signature ends on) against the CIE functions, times the ratio
  ///    sum f(l_i) cmf(l_i) / sum E(l_i) cmf(l_i) of its traced wavelengths: exact where f is
  ///    proportional to E (a matte surface under white light seen through the glass), a ratio
  ///    estimate otherwise.
  /// Colour error then comes from the jumps' positions (< resolution_nm / 2), from jumps that
  /// come and go between two grid wavelengths, and from f's departure from E inside a segment;
  /// not from which wavelengths were drawn: fringes without colour noise.
  void adaptive_transmission(const Vec3& d, const SurfaceInteraction& si, const Vec3& ns,
                             const Vec3& ng, float cos_i, std::uint32_t from, std::uint32_t to,
                             int depth, float b, const SampledWavelengths& w) {
    m_nodes.clear();
    auto add_node = [&](double l, bool traced, double f) {
      m_nodes.push_back({l, chain_end(d, si, ns, ng, from, to, depth, l), 0, f, traced});
    };
    const double hero = w.lambda_nm(0);
    bool hero_added = false;
    for (const double l : m_grid_nm) {  // ascending; the hero goes in its place
      if (!hero_added && hero <= l) {
        add_node(hero, true, transmitted_at(d, si, ns, ng, cos_i, from, to, depth, b, hero, w, 0));
        hero_added = true;
      }
      add_node(l, false, 0.0);
    }
    auto by_lambda = [](const SpectralNode& a, const SpectralNode& c) {
      return a.lambda_nm < c.lambda_nm;
    };
    // Light visibility (shadow rays) only where it can matter: at both ends of each run of equal
    // chain hashes, and inside the run only if those two differ (a shadow edge crossed). A
    // shadow that comes and goes inside such a run is missed, like any jump there and back
    // between two probes.
    for (std::size_t begin = 0; begin < m_nodes.size();) {
      std::size_t end = begin + 1;
      while (end < m_nodes.size() && m_nodes[end].end.hash == m_nodes[begin].end.hash) ++end;
      const std::uint64_t first = full_signature(m_nodes[begin].end);
      const std::uint64_t last = end - begin > 1 ? full_signature(m_nodes[end - 1].end) : first;
      for (std::size_t i = begin; i < end; ++i) {
        SpectralNode& n = m_nodes[i];
        n.signature = i == begin      ? first
                      : i == end - 1  ? last
                      : first == last ? first
                                      : full_signature(n.end);
      }
      begin = end;
    }
    // Bisection between neighbours whose signatures differ, both halves (several jumps may lie
    // between two wavelengths); at most kMaxProbes signatures per split bound the cost where
    // the refracted light crosses many edges (grazing views near a sphere's rim).
    constexpr int kMaxProbes = 64;
    int probes = 0;
    const std::size_t initial = m_nodes.size();
    auto bisect = [&](auto&& self, std::size_t ia, std::size_t ic) -> void {
      const double la = m_nodes[ia].lambda_nm, lc = m_nodes[ic].lambda_nm;
      if (lc - la <= m_resolution_nm || probes >= kMaxProbes) return;
      ++probes;
      add_node(0.5 * (la + lc), false, 0.0);
      const std::size_t im = m_nodes.size() - 1;
      m_nodes[im].signature = full_signature(m_nodes[im].end);
      if (m_nodes[im].signature != m_nodes[ia].signature) self(self, ia, im);
      if (m_nodes[im].signature != m_nodes[ic].signature) self(self, im, ic);
    };
    for (std::size_t i = 0; i + 1 < initial; ++i)
      if (m_nodes[i].signature != m_nodes[i + 1].signature) bisect(bisect, i, i + 1);
    if (m_nodes.size() > initial) std::sort(m_nodes.begin(), m_nodes.end(), by_lambda);
    // Segments: runs of equal signature, bounded halfway between the last node of one run and
    // the first of the next.
    Xyz sum;
    std::size_t begin = 0;
    double lower = kLambdaMinNm;
    while (begin < m_nodes.size()) {
      std::size_t end = begin + 1;
      while (end < m_nodes.size() && m_nodes[end].signature == m_nodes[begin].signature) ++end;
      const double upper = end < m_nodes.size()
                               ? 0.5 * (m_nodes[end - 1].lambda_nm + m_nodes[end].lambda_nm)
                               : kLambdaMaxNm;
      const ReferenceSpectrum reference(m_nodes[begin].end.colour);
      Xyz num, den;
      double f_sum = 0, e_sum = 0;
      auto add = [&](double l, double f) {
        const Xyz bar = cie_xyz_bar(l);
        const double e = illuminant_d65(l) * reference(l);
        num.x += f * bar.x, num.y += f * bar.y, num.z += f * bar.z;
        den.x += e * bar.x, den.y += e * bar.y, den.z += e * bar.z;
        f_sum += f;
        e_sum += e;
      };
      for (std::size_t i = begin; i < end; ++i)
        if (m_nodes[i].traced) add(m_nodes[i].lambda_nm, m_nodes[i].f);
      if (!(e_sum > 1e-6)) {
        // No traced wavelength here, or only where the reference is dark: one lane where the
        // reference is brightest (kept inside the run's probed span, so on its signature).
        const double l = std::clamp(reference.brightest_nm(lower, upper), m_nodes[begin].lambda_nm,
                                    m_nodes[end - 1].lambda_nm);
        add(l, transmitted_at(d, si, ns, ng, cos_i, from, to, depth, b, l, w, -1));
      }
      const Xyz weight = reference.xyz_integral(lower, upper);
      const double ratio = e_sum > 0 ? f_sum / e_sum : 0.0;
      sum.x += weight.x * (den.x > 1e-9 ? num.x / den.x : ratio);
      sum.y += weight.y * (den.y > 1e-9 ? num.y / den.y : ratio);
      sum.z += weight.z * (den.z > 1e-9 ? num.z / den.z : ratio);
      lower = upper;
      begin = end;
    }
    m_side_xyz.x += double(b) * sum.x;
    m_side_xyz.y += double(b) * sum.y;
    m_side_xyz.z += double(b) * sum.z;
  }

  double m_resolution_nm;  // adaptive dispersion: jumps located to this width
  bool m_split;            // dispersion "split" or "adaptive" (else "hero")
  bool m_adaptive;         // dispersion "adaptive"
  Rgb m_background_rgb;
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
    for (std::size_t i = 0; i < m_emission.size(); ++i)
      m_packet.emission[i] = m_emission[i].sample(w);
    m_packet.n.resize(m_scene.media().size());
    for (std::size_t i = 0; i < m_packet.n.size(); ++i)
      m_packet.n[i] = m_dispersive[i] ? m_scene.media()[i].optics.n(w)
                                      : SampledSpectrum(static_cast<float>(m_ior_constant[i]));
    return m_packet;
  }
  std::vector<char> m_dispersive, m_absorbs;
  /// Some medium absorbs: the light's colour then depends on its path lengths, which the
  /// adaptive segments' reference spectra do not model, so dispersion falls back to "split".
  bool m_any_absorbs = false;
  std::vector<double> m_ior_constant;

  std::uint64_t m_adaptive_refractions = 0, m_split_refractions = 0;
  // Outputs of the packet being traced (trace_primary() resets and returns them).
  bool m_split_seen = false;
  Xyz m_side_xyz;
};

/// What every pixel of a spectral render shares: the wavelength stratification and the film's
/// normalisation.
struct SpectralFilm {
  int samples = 1;
  /// wavelength packets of kSpectrumSamples per camera sample where dispersion splits the rays
  int packets = 1;
  /// ratio film: white's exact XYZ under the film's own estimator
  bool ratio = false;
  Xyz white;
  /// shared wavelength pattern: one sub-stratum and one offset for the whole image (from the
  /// seed), the wavelengths of every sub-stratum and white's XYZ under each, computed once
  bool shared = false;
  int shared_first = 0;
  std::vector<SampledWavelengths> shared_wavelengths;
  std::vector<Xyz> shared_white;

  /// Hero wavelength strata: one per pair of camera samples (both samples of a pair carry the
  /// same wavelengths, so the adaptive film's pair differences measure how the image varies over
  /// the pixel, not wavelength noise: render/film/adaptive_pixel.h); one for a single sample.
  /// With adaptive anti-aliasing, as many as the first batch has pairs, cycled by the further
  /// pairs: every pixel then averages the same wavelengths whatever its sample count, so refined
  /// and unrefined pixels of one surface get the same colour.
  static int strata_for(const ImageSettings& st) {
    const int spp =
        st.adaptive ? std::min(st.min_samples, st.samples_per_pixel) : st.samples_per_pixel;
    return (spp + 1) / 2;
  }

  SpectralFilm(const ImageSettings& st, std::uint64_t seed) : samples(strata_for(st)) {
    packets =
        st.dispersion == ImageSettings::Dispersion::split
            ? std::max(1, (st.dispersion_wavelengths + kSpectrumSamples - 1) / kSpectrumSamples)
            : 1;
    // Ratio film: midpoint quadrature over the hero, 4000 cells (D65 and the CIE functions are
    // smooth, error < 1e-6).
    ratio = st.spectral_film == ImageSettings::SpectralFilm::ratio;
    if (ratio) {
      constexpr int kCells = 4000;
      for (int i = 0; i < kCells; ++i) {
        const auto wl = SampledWavelengths::sample((i + 0.5) / kCells);
        const Xyz c = spectrum_to_xyz(illuminant_d65(wl), wl);
        white.x += c.x / kCells, white.y += c.y / kCells, white.z += c.z / kCells;
      }
    }
    shared = st.wavelength_pattern == ImageSettings::WavelengthPattern::shared;
    Pcg32 pattern_rng(0x7468617770617474ULL, seed);  // stream "thawpatt"
    shared_first = int(pattern_rng.next_u32() % std::uint32_t(packets));
    const double shared_jitter = pattern_rng.next_float();
    if (shared) {
      for (int i = 0; i < samples * packets; ++i) {
        shared_wavelengths.push_back(wavelengths_in(i, shared_jitter));
        shared_white.push_back(
            spectrum_to_xyz(illuminant_d65(shared_wavelengths.back()), shared_wavelengths.back()));
      }
    }
  }

  /// The wavelengths of hero sub-stratum `stratum` (of samples x packets) at offset `jitter` in it.
  SampledWavelengths wavelengths_in(int stratum, double jitter) const {
    const double u = (double(stratum) + jitter) / (double(samples) * packets);
    return SampledWavelengths::sample(std::min(u, 1.0 - 1e-12));
  }
};

/// One thread's share of a spectral render. The hero wavelength gets its own strata (one per
/// pair of camera samples, SpectralFilm::strata_for) in a random order per pixel (per_pixel
/// pattern) or a progressive order shared by every pixel (shared pattern).
class SpectralPixelWorker {
 public:
  struct Sample {
    /// the sample's XYZ, white's XYZ under the same wavelengths (ratio film), and the adaptive
    /// dispersion's spectrally integrated light, each averaged over the packets traced
    Xyz xyz, white, side;
    Sample& operator+=(const Sample& o) {
      xyz.x += o.xyz.x, xyz.y += o.xyz.y, xyz.z += o.xyz.z;
      white.x += o.white.x, white.y += o.white.y, white.z += o.white.z;
      side.x += o.side.x, side.y += o.side.y, side.z += o.side.z;
      return *this;
    }
    /// Scaled by a reconstruction filter's weight (render/film/filter.h).
    Sample operator*(float f) const {
      return {{xyz.x * f, xyz.y * f, xyz.z * f},
              {white.x * f, white.y * f, white.z * f},
              {side.x * f, side.y * f, side.z * f}};
    }
  };

  SpectralPixelWorker(const Scene& scene, const SpectralFilm& film,
                      const photon::CausticMap* caustics)
      : m_tracer(scene, caustics),
        m_film(film),
        m_medium(scene.camera_medium()),
        m_lambda_perm(static_cast<std::size_t>(film.samples)) {}

  /// Shared pattern: the strata in a progressive order (bit-reversed: any prefix of a
  /// power-of-two length is evenly spread), the same for every pixel; per_pixel: a random order.
  void start_pixel(Pcg32& rng) {
    if (m_film.shared)
      progressive_order(m_lambda_perm);
    else
      shuffle_indices(m_lambda_perm, rng);
  }

  static void progressive_order(std::vector<int>& order) {
    const auto n = static_cast<std::uint32_t>(order.size());
    std::uint32_t bits = 0;
    while ((1u << bits) < n) ++bits;
    std::size_t k = 0;
    for (std::uint32_t i = 0; k < order.size(); ++i) {
      const std::uint32_t r = bits == 0 ? 0u : sampling::reverse_bits(i) >> (32 - bits);
      if (r < n) order[k++] = static_cast<int>(r);
    }
  }

  Sample sample(const Ray& camera_ray, const CameraSampleContext& camera, Pcg32& rng) {
    // The pair's stratum, cycling over the film's strata (SpectralFilm::strata_for).
    const auto s = static_cast<int>((camera.sample_index / 2) % std::uint32_t(m_film.samples));
    // Wavelength packets: the first always, all of them when the first met a split dispersive
    // refraction. Packet k takes sub-stratum (first + k) mod packets of the sample's hero
    // stratum, at offset `jitter` in it. Per pixel, `first` and `jitter` are random for each
    // sample; shared, they are the same for every pixel (drawn once from the seed): each is
    // uniform, so an unrefined sample's hero is uniform in its stratum and a refined sample's
    // heroes are stratified, in both patterns.
    const int packets = m_film.packets;
    const int first = m_film.shared ? m_film.shared_first
                      : packets > 1 ? int(rng.next_u32() % std::uint32_t(packets))
                                    : 0;
    Xyz sum, white, side;
    int traced = 0;
    for (int k = 0; k < packets; ++k) {
      const int stratum =
          m_lambda_perm[static_cast<std::size_t>(s)] * packets + (first + k) % packets;
      const SampledWavelengths wl =
          m_film.shared ? m_film.shared_wavelengths[static_cast<std::size_t>(stratum)]
                        : m_film.wavelengths_in(stratum, rng.next_float());
      const PacketResult r = m_tracer.trace_primary(camera_ray, m_medium, wl, &camera);
      // The film weighs and averages the samples' XYZ. Negative sRGB (out-of-gamut spectral
      // colours) is kept and clamped at output, so the mean stays unbiased.
      const Xyz c = spectrum_to_xyz(r.radiance, wl);
      sum.x += c.x, sum.y += c.y, sum.z += c.z;
      side.x += r.side_xyz.x, side.y += r.side_xyz.y, side.z += r.side_xyz.z;
      if (m_film.ratio) {
        const Xyz d = m_film.shared ? m_film.shared_white[static_cast<std::size_t>(stratum)]
                                    : spectrum_to_xyz(illuminant_d65(wl), wl);
        white.x += d.x, white.y += d.y, white.z += d.z;
      }
      ++traced;
      if (k == 0 && !r.split_seen) break;
    }
    if (traced > 1) ++m_refined;
    return {{sum.x / traced, sum.y / traced, sum.z / traced},
            {white.x / traced, white.y / traced, white.z / traced},
            {side.x / traced, side.y / traced, side.z / traced}};
  }

  Rgb pixel_value(const Sample& sum, int samples) const {
    Xyz mean{sum.xyz.x / samples, sum.xyz.y / samples, sum.xyz.z / samples};
    if (m_film.ratio) {
      // sum.white > 0: D65 and the CIE functions are positive over 380-780 nm.
      mean = Xyz{sum.xyz.x / sum.white.x * m_film.white.x, sum.xyz.y / sum.white.y * m_film.white.y,
                 sum.xyz.z / sum.white.z * m_film.white.z};
    }
    // The adaptive dispersion's light carries no wavelength-sampling noise: added after the ratio.
    mean.x += sum.side.x / samples, mean.y += sum.side.y / samples, mean.z += sum.side.z / samples;
    const LinearSrgb c = xyz_to_linear_srgb(mean);
    return Rgb(float(c.r), float(c.g), float(c.b));
  }

  void add_counts(RenderStats& stats) const {
    m_tracer.add_counts(stats);
    stats.refined_samples += m_refined;
  }

 private:
  SpectralTracer m_tracer;
  const SpectralFilm& m_film;
  std::uint32_t m_medium;
  std::vector<int> m_lambda_perm;
  std::uint64_t m_refined = 0;
};

}  // namespace

bool spectral_refraction(const Vec3& d, const Vec3& n, double n_from, double n_to, Vec3& out) {
  return refract(d, n, static_cast<float>(static_cast<float>(n_to) / static_cast<float>(n_from)),
                 out);
}

SampledSpectrum trace_spectral_ray(const Scene& scene, const Ray& ray, std::uint32_t medium,
                                   const SampledWavelengths& wavelengths, RenderStats* stats) {
  SpectralTracer tracer(scene);
  const PacketResult r = tracer.trace_primary(ray, medium, wavelengths);
  if (stats) tracer.add_counts(*stats);
  return r.radiance;
}

RenderResult render_spectral(const Scene& scene, const RenderOptions& options,
                             const ProgressCallback& progress, const photon::CausticMap* caustics) {
  const SpectralFilm film(scene.settings(), options.seed);
  return render_image_tiles(scene, options, progress,
                            [&] { return SpectralPixelWorker(scene, film, caustics); });
}

}  // namespace thaw::render
