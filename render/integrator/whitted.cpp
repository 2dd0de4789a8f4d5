#include "render/integrator/whitted.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include "render/integrator/spectral_whitted.h"
#include "render/material/fresnel.h"
#include "render/math/rng.h"

namespace thaw::render {

namespace {

class Tracer {
 public:
  explicit Tracer(const Scene& scene)
      : m_scene(scene),
        m_max_depth(scene.settings().max_depth),
        m_min_weight(static_cast<float>(scene.settings().min_weight)) {
    for (const auto& m : scene.media()) m_ior.push_back(static_cast<float>(m.optics.n_at(media::kFraunhoferD_nm)));
  }

  /// Radiance arriving along `ray` (unit direction), at tree level `depth` (primary = 1), with
  /// accumulated weight `weight`, travelling in `medium`.
  Rgb trace(const Ray& ray, int depth, float weight, std::uint32_t medium) {
    ++rays;
    Hit hit;
    if (!m_scene.intersect(ray, hit)) return m_scene.background();
    const SurfaceInteraction si = m_scene.interaction(ray, hit);
    const SceneObject& obj = m_scene.objects()[si.object];
    if (obj.dielectric) return dielectric(ray, si, obj, depth, weight, medium);
    const Material& mat = m_scene.materials()[obj.material];
    switch (mat.kind) {
      case Material::Kind::emissive:
        return mat.emission;
      case Material::Kind::metal:
        return metal(ray, si, mat, depth, weight, medium);
      case Material::Kind::matte:
      case Material::Kind::phong:
        return phong(ray, si, mat, depth, weight, medium);
    }
    return {};
  }

  std::uint64_t rays = 0, mismatches = 0;

 private:
  Rgb dielectric(const Ray& ray, const SurfaceInteraction& si, const SceneObject& obj, int depth, float weight,
                 std::uint32_t medium) {
    const Vec3& d = ray.direction;
    // The side is decided by the geometric normal, never the shading normal.
    const bool entering = dot(d, si.ng) < 0.0f;
    const std::uint32_t from = entering ? obj.outside : obj.inside;
    const std::uint32_t to = entering ? obj.inside : obj.outside;
    if (medium != from) ++mismatches;
    const float eta = m_ior[to] / m_ior[from];
    const Vec3 ng = entering ? si.ng : -si.ng;  // faces the incident side
    Vec3 ns = entering ? si.ns : -si.ns;
    if (dot(ns, d) >= 0.0f) ns = ng;  // a shading normal facing away would flip the side
    const float cos_i = -dot(d, ns);
    const float r = fresnel_dielectric(cos_i, eta);
    Rgb result;
    if (depth >= m_max_depth) return result;
    if (r > 0.0f && weight * r >= m_min_weight) {
      Vec3 w = reflect(d, ns);
      if (dot(w, ng) <= 0.0f) w = reflect(d, ng);  // shading normal must not send it through
      const Ray next{offset_ray_origin(si.p, si.p_error, ng, w), w};
      result += trace(next, depth + 1, weight * r, from) * r;
    }
    const float t = 1.0f - r;
    if (t > 0.0f && weight * t >= m_min_weight) {
      Vec3 w;
      bool ok = refract(d, ns, eta, w) && dot(w, ng) < 0.0f;
      if (!ok) ok = refract(d, ng, eta, w);
      if (ok) {
        const Ray next{offset_ray_origin(si.p, si.p_error, ng, w), w};
        result += trace(next, depth + 1, weight * t, to) * t;
      }
    }
    return result;
  }

  Rgb metal(const Ray& ray, const SurfaceInteraction& si, const Material& mat, int depth, float weight,
            std::uint32_t medium) {
    const Rgb tint = mat.texture.eval(si.p);
    const float w = weight * tint.max_component();
    if (depth >= m_max_depth || w < m_min_weight || w == 0.0f) return {};
    const Vec3 ng = face_forward(si.ng, -ray.direction);
    Vec3 ns = face_forward(si.ns, ng);
    Vec3 dir = reflect(ray.direction, ns);
    if (dot(dir, ng) <= 0.0f) dir = reflect(ray.direction, ng);
    const Ray next{offset_ray_origin(si.p, si.p_error, ng, dir), dir};
    return tint * trace(next, depth + 1, w, medium);
  }

  Rgb phong(const Ray& ray, const SurfaceInteraction& si, const Material& mat, int depth, float weight,
            std::uint32_t medium) {
    const Vec3& d = ray.direction;
    const Vec3 ng = face_forward(si.ng, -d);
    const Vec3 ns = face_forward(si.ns, ng);
    const Rgb albedo = mat.texture.eval(si.p);
    Rgb result = albedo * m_scene.ambient() * mat.ka;
    for (const PointLight& light : m_scene.lights()) {
      const Vec3 to_light = light.position - si.p;
      const float dist2 = dot(to_light, to_light);
      if (!(dist2 > 0.0f)) continue;
      const Vec3 l = to_light / std::sqrt(dist2);
      if (dot(l, ng) <= 0.0f) continue;  // light behind the surface
      const float cos_l = dot(ns, l);
      if (cos_l <= 0.0f) continue;
      const Vec3 origin = offset_ray_origin(si.p, si.p_error, ng, l);
      // Unnormalised direction: the light sits at t = 1; stop just short of it.
      const Ray shadow{origin, light.position - origin, 1.0f - 1e-4f};
      ++rays;
      if (m_scene.occluded(shadow)) continue;
      Rgb li = light.radiance;
      if (light.inverse_square) li *= 1.0f / dist2;
      result += albedo * li * (mat.kd * cos_l);
      if (mat.ks > 0.0f) {
        const float s = dot(reflect(-l, ns), -d);
        if (s > 0.0f) result += li * (mat.ks * std::pow(s, mat.shininess));
      }
    }
    if (mat.kind != Material::Kind::phong || depth >= m_max_depth) return result;
    if (mat.reflectance > 0.0f && weight * mat.reflectance >= m_min_weight) {
      Vec3 w = reflect(d, ns);
      if (dot(w, ng) <= 0.0f) w = reflect(d, ng);
      const Ray next{offset_ray_origin(si.p, si.p_error, ng, w), w};
      result += trace(next, depth + 1, weight * mat.reflectance, medium) * mat.reflectance;
    }
    if (mat.transmittance > 0.0f && weight * mat.transmittance >= m_min_weight) {
      // The classic model: ior relative to the front side; the carried medium is not changed.
      const bool entering = dot(d, si.ng) < 0.0f;
      const float eta = entering ? mat.ior : 1.0f / mat.ior;
      Vec3 w;
      if (refract(d, ns, eta, w) && dot(w, ng) < 0.0f) {
        const Ray next{offset_ray_origin(si.p, si.p_error, ng, w), w};
        result += trace(next, depth + 1, weight * mat.transmittance, medium) * mat.transmittance;
      }
    }
    return result;
  }

  const Scene& m_scene;
  int m_max_depth;
  float m_min_weight;
  std::vector<float> m_ior;
};

}  // namespace

Rgb trace_ray(const Scene& scene, const Ray& ray, std::uint32_t medium, RenderStats* stats) {
  Tracer tracer(scene);
  const Rgb c = tracer.trace(ray, 1, 1.0f, medium);
  if (stats) {
    stats->rays += tracer.rays;
    stats->medium_mismatches += tracer.mismatches;
  }
  return c;
}

RenderResult render(const Scene& scene, const RenderOptions& options, const ProgressCallback& progress) {
  if (scene.spectral()) return render_spectral(scene, options, progress);
  const auto start = std::chrono::steady_clock::now();
  const ImageSettings& st = scene.settings();
  const int w = st.width, h = st.height, spp = st.samples_per_pixel;
  const int tile = std::max(1, options.tile_size);
  const int tiles_x = (w + tile - 1) / tile, tiles_y = (h + tile - 1) / tile;
  const int tiles = tiles_x * tiles_y;
  RenderResult result;
  result.image = Image(w, h);
  const int threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  // Stratification: an m x m grid when spp is a square, otherwise a Latin hypercube (one sample
  // per row and column stratum); a single sample goes through the pixel centre (as POV-Ray).
  const int grid = static_cast<int>(std::lround(std::sqrt(double(spp))));
  const bool square = grid * grid == spp;
  std::uint64_t rays = 0, mismatches = 0;
  std::atomic<std::int64_t> tiles_done{0};
#pragma omp parallel num_threads(threads) reduction(+ : rays, mismatches)
  {
    Tracer tracer(scene);
    std::vector<int> perm(static_cast<std::size_t>(spp));
#pragma omp for schedule(dynamic, 1)
    for (int t = 0; t < tiles; ++t) {
      const int x0 = (t % tiles_x) * tile, y0 = (t / tiles_x) * tile;
      const int x1 = std::min(x0 + tile, w), y1 = std::min(y0 + tile, h);
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
          Rgb sum;
          if (spp == 1) {
            sum = tracer.trace(scene.camera().generate(float(x) + 0.5f, float(y) + 0.5f), 1, 1.0f,
                               scene.camera_medium());
          } else {
            Pcg32 rng(std::uint64_t(y) * std::uint64_t(w) + std::uint64_t(x), options.seed);
            if (!square) {
              for (int i = 0; i < spp; ++i) perm[static_cast<std::size_t>(i)] = i;
              for (int i = spp - 1; i > 0; --i)
                std::swap(perm[static_cast<std::size_t>(i)], perm[rng.next_u32() % static_cast<std::uint32_t>(i + 1)]);
            }
            for (int s = 0; s < spp; ++s) {
              float sx, sy;
              if (square) {
                sx = (float(s % grid) + rng.next_float()) / float(grid);
                sy = (float(s / grid) + rng.next_float()) / float(grid);
              } else {
                sx = (float(s) + rng.next_float()) / float(spp);
                sy = (float(perm[static_cast<std::size_t>(s)]) + rng.next_float()) / float(spp);
              }
              // Box filter of one pixel: the samples' mean.
              sum += tracer.trace(scene.camera().generate(float(x) + sx, float(y) + sy), 1, 1.0f,
                                  scene.camera_medium());
            }
            sum *= 1.0f / float(spp);
          }
          result.image.at(x, y) = sum;
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
  result.stats.threads = threads;
  result.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.stats.rays_per_second = result.stats.seconds > 0 ? double(rays) / result.stats.seconds : 0.0;
  return result;
}

}  // namespace thaw::render
