// Photon paths through dielectrics; see photon_tracer.h.
#include "render/photon/photon_tracer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

#include "render/material/fresnel.h"
#include "render/material/microfacet.h"
#include "render/photon/low_discrepancy.h"

namespace thaw::render::photon {

namespace {

/// Linear interpolation in a 1 nm table starting at 380 nm.
float lookup(const std::vector<float>& table, double lambda_nm) {
  if (table.size() == 1) return table[0];
  const double x = std::clamp(lambda_nm - kLambdaMinNm, 0.0, double(table.size() - 1));
  const auto i = std::min(static_cast<std::size_t>(x), table.size() - 2);
  const double t = x - double(i);
  return static_cast<float>(table[i] * (1.0 - t) + table[i + 1] * t);
}

/// Two uniform numbers in [0, 1) from where and how a photon meets a surface (splitmix64 over the
/// bits of its point, direction and level): a rough interface's microfacet normal that depends on
/// the photon alone, never on the thread or the order photons are traced in.
std::pair<float, float> hash_uniforms(const Vec3& p, const Vec3& d, int depth) {
  auto bits = [](float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return std::uint64_t(u);
  };
  std::uint64_t h = bits(p.x) ^ (bits(p.y) << 21) ^ (bits(p.z) << 42) ^ std::uint64_t(depth) << 60;
  h ^= bits(d.x) * 0x9e3779b97f4a7c15ULL ^ bits(d.y) * 0xc2b2ae3d27d4eb4fULL ^
       bits(d.z) * 0x165667b19e3779f9ULL;
  auto mix = [](std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  const std::uint64_t a = mix(h + 0x9e3779b97f4a7c15ULL), b = mix(a);
  return {float(a >> 40) * 0x1p-24f, float(b >> 40) * 0x1p-24f};
}

struct Branch {
  Ray ray;
  std::uint32_t medium;
  float weight;
  int depth;
  bool caustic;
  /// RGB absorption kept so far, per channel (PathEvent::tint)
  Rgb tint;
  /// index-matched interfaces crossed (they cost no depth level; bounded against degenerate scenes)
  int matched = 0;
};

/// Index-matched interfaces one branch may cross.
constexpr int kMaxMatchedCrossings = 1024;

/// The k-th roulette decision of photon `index`, uniform in [0, 1): Halton dimensions 5-7 (the
/// first three decisions: stratified across photons), then a fixed hash (SplitMix64, Steele et
/// al. 2014) of the index and k.
double roulette_number(std::uint64_t index, int k) {
  if (k < ScrambledHalton::kDimensions - 5) return ScrambledHalton::sample(index, 5 + k);
  std::uint64_t z =
      index * 0x9e3779b97f4a7c15ULL + static_cast<std::uint64_t>(k) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1p-53;
}

/// Levels followed at most (the parser's limit of [image] max_depth).
constexpr int kMaxDepth = 64;
/// Deepest explicit stack a path can need: every level pops one branch and pushes at most two,
/// so the stack holds at most one branch per level plus one.
constexpr int kMaxStack = kMaxDepth + 2;

}  // namespace

PhotonTracer::PhotonTracer(const Scene& scene, float roulette_weight)
    : m_scene(scene),
      m_spectral(photons_carry_wavelengths(scene)),
      m_max_depth(std::min(scene.settings().max_depth, kMaxDepth)),
      m_min_weight(static_cast<float>(scene.settings().min_weight)),
      m_roulette_weight(roulette_weight) {
  const int samples = static_cast<int>(kLambdaMaxNm - kLambdaMinNm) + 1;
  for (const auto& m : scene.media()) {
    std::vector<float> n, alpha;
    Rgb alpha_rgb;
    if (!m_spectral) {
      n.push_back(static_cast<float>(m.optics.n_at(media::kFraunhoferD_nm)));
      const LinearSrgb a = m.optics.absorption().srgb_per_m();
      alpha_rgb = Rgb{float(a.r), float(a.g), float(a.b)};
    } else {
      for (int i = 0; i < samples; ++i)
        n.push_back(static_cast<float>(m.optics.n_at(kLambdaMinNm + i)));
      if (m.optics.absorbs())
        for (int i = 0; i < samples; ++i)
          alpha.push_back(static_cast<float>(m.optics.absorption_per_m_at(kLambdaMinNm + i)));
    }
    m_ior.push_back(std::move(n));
    m_alpha.push_back(std::move(alpha));
    m_alpha_rgb.push_back(alpha_rgb);
  }
}

bool photons_carry_wavelengths(const Scene& scene) {
  if (!scene.spectral()) return false;
  for (const auto& m : scene.media())
    if (m.optics.is_dispersive() || m.optics.absorbs()) return true;
  return false;
}

float PhotonTracer::ior(std::uint32_t m, double lambda_nm) const {
  return lookup(m_ior[m], lambda_nm);
}

float PhotonTracer::absorption_per_m(std::uint32_t m, double lambda_nm) const {
  return m_alpha[m].empty() ? 0.0f : lookup(m_alpha[m], lambda_nm);
}

std::uint32_t medium_at(const Scene& scene, const Vec3& p) {
  Ray ray{p, Vec3{0.0f, 1.0f, 0.0f}};
  for (int i = 0; i < 1024; ++i) {
    Hit hit;
    if (!scene.intersect(ray, hit)) break;
    const SurfaceInteraction si = scene.interaction(ray, hit);
    const SceneObject& obj = scene.objects()[si.object];
    if (obj.dielectric) return dot(ray.direction, si.ng) > 0.0f ? obj.inside : obj.outside;
    ray.origin = offset_ray_origin(si.p, si.p_error, si.ng, ray.direction);  // past opaque ones
  }
  return scene.camera_medium();
}

std::uint32_t PhotonTracer::medium_at(const Vec3& p) const {
  return photon::medium_at(m_scene, p);
}

std::uint32_t PhotonTracer::trace(const Ray& start, std::uint32_t medium, double lambda_nm,
                                  PathEvents& events, std::uint64_t photon_index) const {
  events.clear();
  // Uninitialised storage: constructing kMaxStack branches per photon cost ~10 % of the pass.
  // Assigning a Branch (trivially copyable) to a slot begins its lifetime ([class.union]).
  union Slot {
    Slot() {}
    Branch b;
  };
  Slot slots[kMaxStack];
  struct {
    Slot* s;
    Branch& operator[](int i) { return s[i].b; }
  } stack{slots};
  int top = 0;
  const Rgb white{1.0f, 1.0f, 1.0f};
  stack[top++] = Branch{start, medium, 1.0f, 0, false, white, 0};
  Rgb tint = white;  // the current branch's
  auto end = [&](PathEnd how, const Vec3& p, const Vec3& n, float w) {
    if (w != 0.0f) events.push_back(PathEvent{how, p, n, w, tint});
  };
  int decisions = 0;
  // Whether a new branch of weight w at p is followed; w may be raised by the roulette.
  auto keep = [&](float& w, const Vec3& p, const Vec3& d) {
    if (m_roulette_weight > 0.0f && w < m_roulette_weight) {
      const double u = roulette_number(photon_index, decisions++);
      if (u * m_roulette_weight >= w) {
        end(PathEnd::roulette, p, d, w);
        return false;
      }
      end(PathEnd::roulette, p, d, w - m_roulette_weight);
      w = m_roulette_weight;
      return true;
    }
    if (w < m_min_weight) {
      end(PathEnd::cut, p, d, w);
      return false;
    }
    return true;
  };
  std::uint32_t rays = 0;
  while (top > 0) {
    Branch b = stack[--top];
    tint = b.tint;
    Hit hit;
    ++rays;
    if (!m_scene.intersect(b.ray, hit)) {
      // Leaving through an absorbing medium keeps nothing (an infinite path), as for camera rays.
      const bool absorbing =
          absorption_per_m(b.medium, lambda_nm) > 0.0f || !m_alpha_rgb[b.medium].is_black();
      end(absorbing   ? PathEnd::absorbed
          : b.caustic ? PathEnd::escaped
                      : PathEnd::direct,
          b.ray.origin, b.ray.direction, b.weight);
      continue;
    }
    const float alpha = absorption_per_m(b.medium, lambda_nm);
    if (alpha > 0.0f) {
      const float kept = b.weight * std::exp(-alpha * hit.t);  // unit direction: t is the length
      end(PathEnd::absorbed, b.ray.origin, b.ray.direction, b.weight - kept);
      b.weight = kept;
    }
    if (const Rgb& a = m_alpha_rgb[b.medium]; !a.is_black()) {
      // RGB: the channels keep exp(-alpha_c t); the lost share is an absorbed event.
      const auto t = double(hit.t);
      const Rgb kept = b.tint * Rgb{float(std::exp(-a.r * t)), float(std::exp(-a.g * t)),
                                    float(std::exp(-a.b * t))};
      tint = Rgb{b.tint.r - kept.r, b.tint.g - kept.g, b.tint.b - kept.b};
      end(PathEnd::absorbed, b.ray.origin, b.ray.direction, b.weight);
      tint = b.tint = kept;
    }
    const SurfaceInteraction si = m_scene.interaction(b.ray, hit);
    const SceneObject& obj = m_scene.objects()[si.object];
    const Vec3& d = b.ray.direction;
    if (!obj.dielectric) {
      const Material::Kind kind = m_scene.materials()[obj.material].kind;
      const bool diffuse = kind == Material::Kind::matte || kind == Material::Kind::phong;
      const PathEnd how = !diffuse    ? PathEnd::stopped
                          : b.caustic ? PathEnd::stored
                                      : PathEnd::direct;
      end(how, si.p, face_forward(si.ng, -d), b.weight);
      continue;
    }
    // The interface: the same side, media, normals and fallbacks as the Whitted integrator.
    const bool entering = dot(d, si.ng) < 0.0f;
    const std::uint32_t from = entering ? obj.outside : obj.inside;
    const std::uint32_t to = entering ? obj.inside : obj.outside;
    const Vec3 ng = entering ? si.ng : -si.ng;  // faces the incident side
    if (obj.index_matched) {
      // Invisible (R = 0, no bending, no absorption): straight on into the other medium, no
      // depth level used, so an index-matched object changes nothing downstream.
      if (b.matched >= kMaxMatchedCrossings) {
        end(PathEnd::cut, si.p, d, b.weight);
        continue;
      }
      stack[top++] = Branch{Ray{offset_ray_origin(si.p, si.p_error, ng, d), d},
                            to,
                            b.weight,
                            b.depth,
                            b.caustic,
                            b.tint,
                            b.matched + 1};
      continue;
    }
    if (b.depth + 1 >= m_max_depth) {
      end(PathEnd::cut, si.p, d, b.weight);
      continue;
    }
    const float eta = ior(to, lambda_nm) / ior(from, lambda_nm);
    Vec3 ns = entering ? si.ns : -si.ns;
    if (dot(ns, d) >= 0.0f) ns = ng;
    // A rough interface (render/material/microfacet.h): the photon meets one visible normal m,
    // which stands in for the normal below, and each branch is weighed by G2 / G1 and the
    // compensation of the side it comes from, as camera rays are (whitted_shading.h).
    float g_r = 1.0f, g_t = 1.0f;
    if (obj.alpha > 0.0f) {
      const microfacet::Frame frame(ns);
      const Vec3 wo = frame.to_local(-d);
      const auto [u1, u2] = hash_uniforms(si.p, d, b.depth);
      const Vec3 m = microfacet::sample_visible_normal(wo, obj.alpha, u1, u2);
      const float c = dot(wo, m);
      if (!(c > 0.0f) || wo.z <= 0.0f) {
        end(PathEnd::cut, si.p, d, b.weight);
        continue;
      }
      const float k =
          (entering ? obj.albedo_entering : obj.albedo_leaving)->dielectric_compensation(wo.z) /
          microfacet::ggx_g1(wo, obj.alpha);
      const Vec3 wr = m * (2.0f * c) - wo;
      g_r = wr.z > 0.0f && dot(frame.to_world(wr), ng) > 0.0f
                ? microfacet::ggx_g2(wo, wr, obj.alpha) * k
                : 0.0f;
      Vec3 wt;
      g_t = microfacet::refract_about(wo, m, eta, wt) && wt.z < 0.0f &&
                    dot(frame.to_world(wt), ng) < 0.0f
                ? microfacet::ggx_g2(wo, wt, obj.alpha) * k
                : 0.0f;
      ns = normalize(frame.to_world(m));
    }
    const float r = fresnel_dielectric(-dot(d, ns), eta);
    float wr = b.weight * r * g_r, wt = b.weight * (1.0f - r) * g_t;
    if (obj.alpha > 0.0f) {
      // What the compensation does not restore (a branch below the surface) ends here.
      const float lost = b.weight - wr - wt;
      if (lost > 0.0f) end(PathEnd::cut, si.p, d, lost);
    }
    if (wr > 0.0f && keep(wr, si.p, d)) {
      Vec3 w = reflect(d, ns);
      if (dot(w, ng) <= 0.0f) w = reflect(d, ng);
      stack[top++] = Branch{Ray{offset_ray_origin(si.p, si.p_error, ng, w), w},
                            from,
                            wr,
                            b.depth + 1,
                            true,
                            b.tint,
                            b.matched};
    }
    if (wt > 0.0f) {
      Vec3 w;
      bool ok = refract(d, ns, eta, w) && dot(w, ng) < 0.0f;
      if (!ok) ok = refract(d, ng, eta, w);
      if (!ok) {
        end(PathEnd::cut, si.p, d, wt);
      } else if (keep(wt, si.p, d)) {
        stack[top++] = Branch{Ray{offset_ray_origin(si.p, si.p_error, ng, w), w},
                              to,
                              wt,
                              b.depth + 1,
                              true,
                              b.tint,
                              b.matched};
      }
    }
  }
  return rays;
}

}  // namespace thaw::render::photon
