#include "render/integrator/spectral_whitted.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
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

class SpectralTracer {
 public:
  explicit SpectralTracer(const Scene& scene)
      : m_scene(scene),
        m_max_depth(scene.settings().max_depth),
        m_min_weight(static_cast<float>(scene.settings().min_weight)),
        m_resolution_nm(scene.settings().dispersion_resolution_nm),
        m_split(scene.settings().dispersion != ImageSettings::Dispersion::hero),
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

  std::uint64_t rays = 0, mismatches = 0, adaptive_refractions = 0, split_refractions = 0;

  /// Set when some dispersive refraction was split into lanes (render_spectral then traces the
  /// camera sample's remaining wavelength packets). Before its first dispersive refraction a ray
  /// tree is the same for every wavelength, so this depends on the camera ray alone, never on
  /// the sampled wavelengths: refining where it is set keeps the estimator unbiased.
  bool split_seen = false;

  /// Adaptive spectral integration of the light transmitted at split dispersive refractions
  /// (dispersion = "adaptive"; see adaptive_transmission). Its XYZ goes to `side_xyz`, not into
  /// the returned spectrum; render_spectral adds it to the film outside the ratio normalisation.
  bool adaptive = false;
  Xyz side_xyz;

 private:
  /// Where the main chain of one wavelength ends (see chain_end()).
  struct ChainEnd {
    std::uint64_t hash = 0;  // objects met, total reflections, end colour (not the lights)
    Rgb colour{1.0f, 1.0f, 1.0f};  // colour it ends on: reference spectrum of its segment
    bool lit = false;        // ends on a diffuse surface, whose light visibility matters
    Vec3 p, p_error, g, s;   // that surface point, its error bound, normals facing the chain
  };
  struct SpectralNode {
    double lambda_nm;
    ChainEnd end;
    std::uint64_t signature;  // end.hash and the lights it sees (set once probed)
    double f;      // transmitted radiance t(l) L(l) at this wavelength; valid where traced
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
      const auto i = std::clamp<std::ptrdiff_t>(std::lower_bound(cdf.begin(), cdf.end(), u) - cdf.begin(), 1,
                                                std::ptrdiff_t(cdf.size()) - 1);
      const double t = (u - cdf[i - 1]) / (cdf[i] - cdf[i - 1]);
      m_grid_nm[static_cast<std::size_t>(g)] = kLambdaMinNm + double(i - 1) + std::clamp(t, 0.0, 1.0);
    }
    m_grid_nm.front() = kLambdaMinNm;
    m_grid_nm.back() = kLambdaMaxNm;
  }

  double index_at(std::uint32_t medium, double lambda_nm) const {
    return m_dispersive[medium] ? m_scene.media()[medium].optics.n_at(lambda_nm)
                                : m_ior_constant[medium];
  }

  /// Snell's direction with the shading normal, falling back to the geometric one; false on
  /// total internal reflection. Normals face the incident side.
  static bool refraction_direction(const Vec3& d, const Vec3& ns, const Vec3& ng, float eta,
                                   Vec3& dir) {
    if (refract(d, ns, eta, dir) && dot(dir, ng) < 0.0f) return true;
    return refract(d, ng, eta, dir);
  }
  /// Mirror direction about the shading normal, about the geometric one if that would go below.
  static Vec3 reflection_direction(const Vec3& d, const Vec3& ns, const Vec3& ng) {
    const Vec3 dir = reflect(d, ns);
    return dot(dir, ng) <= 0.0f ? reflect(d, ng) : dir;
  }

  /// A dielectric interface as ray direction d meets it: the medium it comes from and goes to,
  /// the normals turned to face d's side (shading normal replaced by the geometric one where it
  /// faces away).
  struct FacingInterface {
    std::uint32_t from, to;
    Vec3 ng, ns;
  };
  static FacingInterface facing(const Vec3& d, const SurfaceInteraction& si,
                                const SceneObject& obj) {
    const bool entering = dot(d, si.ng) < 0.0f;
    FacingInterface f{entering ? obj.outside : obj.inside, entering ? obj.inside : obj.outside,
                      entering ? si.ng : -si.ng, entering ? si.ns : -si.ns};
    if (dot(f.ns, d) >= 0.0f) f.ns = f.ng;
    return f;
  }

  /// How point light `light` meets surface point p (normals ng, ns facing the viewer): behind
  /// the surface (no shadow ray cast), shadowed, or seen; l, cos_l, dist2 describe the
  /// direction to it.
  enum class LightVisibility { facing_away, shadowed, seen };
  LightVisibility light_visibility(const Vec3& p, const Vec3& p_error, const Vec3& ng,
                                   const Vec3& ns, const PointLight& light, Vec3& l, float& cos_l,
                                   float& dist2) {
    const Vec3 to_light = light.position - p;
    dist2 = dot(to_light, to_light);
    if (!(dist2 > 0.0f)) return LightVisibility::facing_away;
    l = to_light / std::sqrt(dist2);
    if (dot(l, ng) <= 0.0f) return LightVisibility::facing_away;
    cos_l = dot(ns, l);
    if (cos_l <= 0.0f) return LightVisibility::facing_away;
    const Vec3 origin = offset_ray_origin(p, p_error, ng, l);
    ++rays;
    return m_scene.occluded(Ray{origin, light.position - origin, 1.0f - 1e-4f})
               ? LightVisibility::shadowed
               : LightVisibility::seen;
  }

  static bool is_grey(const SampledSpectrum& s) {
    for (int i = 1; i < kSpectrumSamples; ++i)
      if (s[i] != s[0]) return false;
    return true;
  }

  static std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
    // FNV-1a over 64-bit words: order-sensitive, cheap; collisions only merge segments.
    return (h ^ v) * 1099511628211ULL;
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
    std::uint64_t h = 1469598103934665603ULL;
    for (int level = depth + 1; level <= m_max_depth; ++level) {
      ++rays;
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
        const FacingInterface fi = facing(rd, si, obj);
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
  /// (shadow rays, as phong() casts them).
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
      return double(t) * double(trace(next, depth + 1, beta, to, w, lane)[lane]);
    }
    const SampledWavelengths single = SampledWavelengths::from(
        SampledSpectrum(static_cast<float>(lambda_nm)), SampledSpectrum(1.0f));
    beta[0] = b * t;
    return double(t) * double(trace(next, depth + 1, beta, to, single, 0)[0]);
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
        n.signature = i == begin ? first
                      : i == end - 1 ? last
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
    side_xyz.x += double(b) * sum.x;
    side_xyz.y += double(b) * sum.y;
    side_xyz.z += double(b) * sum.z;
  }

  SampledSpectrum dielectric(const Ray& ray, const SurfaceInteraction& si, const SceneObject& obj, int depth,
                             const SampledSpectrum& beta, std::uint32_t medium, const SampledWavelengths& w,
                             int lane) {
    const Vec3& d = ray.direction;
    const auto [from, to, ng, ns] = facing(d, si, obj);
    if (medium != from) ++mismatches;
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
        for (int i = 0; i < kSpectrumSamples; ++i)
          r[i] = fresnel_dielectric(cos_i, n_to[i] / n_from[i]);
      }
    }
    // Reflected branch: every carried wavelength, each with its own Fresnel reflectance.
    if (!r.is_black() && live_max(beta * r, w) >= m_min_weight) {
      const Vec3 dir = reflection_direction(d, ns, ng);
      const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
      result += trace(next, depth + 1, beta * r, from, w, lane) * r;
    }
    const SampledSpectrum t = SampledSpectrum(1.0f) - r;
    if (dispersive && lane < 0 && m_split && !w.secondary_terminated()) {
      split_seen = true;
      if (adaptive && !m_any_absorbs && is_grey(beta)) {
        // Upstream throughput independent of the wavelength: integrate the transmitted light
        // over the whole spectrum here (its XYZ goes to side_xyz).
        ++adaptive_refractions;
        adaptive_transmission(d, si, ns, ng, cos_i, from, to, depth, beta[0], w);
        return result;
      }
      ++split_refractions;
      // Split: each carried wavelength refracts its own way on its own ray (4 rays). Every
      // wavelength's radiance is then exact, so the film estimator keeps all four: no colour
      // noise beyond the wavelength sampling itself.
      for (int i = 0; i < kSpectrumSamples; ++i) {
        SampledSpectrum mask;
        mask[i] = t[i];
        const SampledSpectrum b = beta * mask;
        if (!(b[i] >= m_min_weight) || b[i] == 0.0f) continue;
        Vec3 dir;
        if (!refraction_direction(d, ns, ng, n_to[i] / n_from[i], dir)) continue;
        const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
        result += trace(next, depth + 1, b, to, w, i) * mask;
      }
      return result;
    }
    Vec3 dir;
    if (!refraction_direction(d, ns, ng, eta_hero, dir)) return result;
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
    const Vec3 ns = face_forward(si.ns, ng);
    const Vec3 dir = reflection_direction(ray.direction, ns, ng);
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
      Vec3 l;
      float cos_l, dist2;
      if (light_visibility(si.p, si.p_error, ng, ns, light, l, cos_l, dist2) !=
          LightVisibility::seen)
        continue;
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
      const Vec3 dir = reflection_direction(d, ns, ng);
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
  double m_resolution_nm;  // adaptive dispersion: jumps located to this width
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
  const int packets =
      st.dispersion == ImageSettings::Dispersion::split
          ? std::max(1, (st.dispersion_wavelengths + kSpectrumSamples - 1) / kSpectrumSamples)
          : 1;
  // Shared wavelength pattern: one sub-stratum and one offset for the whole image, from the seed.
  const bool pattern_shared = st.wavelength_pattern == ImageSettings::WavelengthPattern::shared;
  Pcg32 pattern_rng(0x7468617770617474ULL, options.seed);  // stream "thawpatt"
  const int shared_first = int(pattern_rng.next_u32() % std::uint32_t(packets));
  const double shared_jitter = pattern_rng.next_float();
  // The wavelengths of hero sub-stratum `stratum` (of spp x packets) at offset `jitter` in it;
  // with the shared pattern all of them, and white's XYZ under each, are computed once here.
  auto wavelengths_in = [&](int stratum, double jitter) {
    const double u = (double(stratum) + jitter) / (double(spp) * packets);
    return SampledWavelengths::sample(std::min(u, 1.0 - 1e-12));
  };
  std::vector<SampledWavelengths> shared_wavelengths;
  std::vector<Xyz> shared_white;
  if (pattern_shared) {
    for (int i = 0; i < spp * packets; ++i) {
      shared_wavelengths.push_back(wavelengths_in(i, shared_jitter));
      shared_white.push_back(spectrum_to_xyz(illuminant_d65(shared_wavelengths.back()), shared_wavelengths.back()));
    }
  }
  std::uint64_t rays = 0, mismatches = 0, refined = 0, adaptive_refractions = 0,
                split_refractions = 0;
  std::atomic<std::int64_t> tiles_done{0};
#pragma omp parallel num_threads(threads) \
    reduction(+ : rays, mismatches, refined, adaptive_refractions, split_refractions)
  {
    SpectralTracer tracer(scene);
    tracer.adaptive = st.dispersion == ImageSettings::Dispersion::adaptive;
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
          // side_sum: light integrated over the spectrum at adaptive dispersive refractions; it
          // carries no wavelength-sampling noise, so it is added after the ratio normalisation.
          Xyz sum, white_sum, side_sum;
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
            const int first = pattern_shared ? shared_first
                              : packets > 1  ? int(rng.next_u32() % std::uint32_t(packets))
                                             : 0;
            const Ray camera_ray = scene.camera().generate(float(x) + sx, float(y) + sy);
            Xyz sample_sum, sample_white, sample_side;
            int traced = 0;
            for (int k = 0; k < packets; ++k) {
              const int stratum = lambda_perm[static_cast<std::size_t>(s)] * packets + (first + k) % packets;
              const SampledWavelengths wl =
                  pattern_shared ? shared_wavelengths[static_cast<std::size_t>(stratum)]
                                 : wavelengths_in(stratum, rng.next_float());
              tracer.split_seen = false;
              tracer.side_xyz = Xyz{};
              const SampledSpectrum l =
                  tracer.trace(camera_ray, 1, SampledSpectrum(1.0f), scene.camera_medium(), wl);
              // Box filter: the mean of the samples' XYZ. Negative sRGB (out-of-gamut spectral
              // colours) is kept and clamped at output, so the mean stays unbiased.
              const Xyz c = spectrum_to_xyz(l, wl);
              sample_sum.x += c.x, sample_sum.y += c.y, sample_sum.z += c.z;
              sample_side.x += tracer.side_xyz.x, sample_side.y += tracer.side_xyz.y;
              sample_side.z += tracer.side_xyz.z;
              if (ratio) {
                const Xyz d = pattern_shared ? shared_white[static_cast<std::size_t>(stratum)]
                                             : spectrum_to_xyz(illuminant_d65(wl), wl);
                sample_white.x += d.x, sample_white.y += d.y, sample_white.z += d.z;
              }
              ++traced;
              if (k == 0 && !tracer.split_seen) break;
            }
            if (traced > 1) ++refined;
            sum.x += sample_sum.x / traced, sum.y += sample_sum.y / traced,
                sum.z += sample_sum.z / traced;
            white_sum.x += sample_white.x / traced, white_sum.y += sample_white.y / traced;
            white_sum.z += sample_white.z / traced;
            side_sum.x += sample_side.x / traced, side_sum.y += sample_side.y / traced;
            side_sum.z += sample_side.z / traced;
          }
          Xyz mean{sum.x / spp, sum.y / spp, sum.z / spp};
          if (ratio) {
            // white_sum > 0: D65 and the CIE functions are positive over 380-780 nm.
            mean = Xyz{sum.x / white_sum.x * white.x, sum.y / white_sum.y * white.y,
                       sum.z / white_sum.z * white.z};
          }
          mean.x += side_sum.x / spp, mean.y += side_sum.y / spp, mean.z += side_sum.z / spp;
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
    adaptive_refractions += tracer.adaptive_refractions;
    split_refractions += tracer.split_refractions;
  }
  result.stats.rays = rays;
  result.stats.medium_mismatches = mismatches;
  result.stats.refined_samples = refined;
  result.stats.adaptive_refractions = adaptive_refractions;
  result.stats.split_refractions = split_refractions;
  result.stats.threads = threads;
  result.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.stats.rays_per_second = result.stats.seconds > 0 ? double(rays) / result.stats.seconds : 0.0;
  return result;
}

}  // namespace thaw::render
