#pragma once
// Caustics: light from the point lights that reaches diffuse surfaces through dielectrics
// (refracted, reflected, absorbed and dispersed), found by one photon pass per frame and
// returned as irradiance E for the integrator to add at a diffuse hit as albedo * kd * E, beside
// the direct light (which the dielectrics shadow: nothing is counted twice, photon_tracer.h).
//
// The pass: photons are aimed from each light into the cones of the dielectric objects'
// bounding spheres (light_cone.h), N_k of them into cone k, their directions and wavelengths the
// points of a scrambled Halton sequence (low_discrepancy.h: the same points every frame and for
// any thread count, so frames do not flicker), traced by photon_tracer.h and stored on diffuse
// surfaces into a photon_map.h. Photon power (RGB):
//   falloff = "inverse_square": Phi = I Omega_k / N_k, so that the density estimate returns
//     E = I cos(theta) / d^2 exactly as the direct light does;
//   falloff = "none" (POV-Ray): direct light is E = I cos(theta) at any distance, which no
//     photon flux can reproduce everywhere; photons carry Phi = I D_k^2 Omega_k / N_k, D_k the
//     distance from the light to the target's centre, so the caustic has the brightness the
//     direct light has at the object's distance (and then falls off as 1/d^2 beyond, as light
//     does).
// In spectral scenes a photon carries one wavelength (Halton dimension 2, drawn with the visible
// density of the film) and its power is the sRGB of the light's uplifted spectrum at that
// wavelength: Phi_rgb = scale * M_xyz->srgb (S(lambda) cmf(lambda)) / p(lambda), which averages
// to the light's colour (a white light's photons sum to white).
// Photons are traced in fixed chunks in parallel (OpenMP) and stored in photon index order, so
// the map does not depend on the thread count. Nothing throws inside the parallel loop.
#include <cstdint>

#include "render/math/color.h"
#include "render/photon/photon_map.h"
#include "render/scene/scene.h"

namespace thaw::render::photon {

/// Automatic photon count (all lights together) when [caustics] photons is not set.
inline constexpr long long kDefaultPhotons = 250000;
/// Automatic radius: photons expected in the kernel's disc where the light is not focused.
inline constexpr double kPhotonsPerDisc = 64.0;

/// Branches lighter than this fraction of their photon's power are decided by Russian roulette
/// (photon_tracer.h): the entry reflection and internal reflections of ice (R ~ 2-4 %) go on
/// in 1 of ~8 photons, which halves the rays per photon without bias.
inline constexpr float kRouletteWeight = 0.25f;

/// Power of a group of photons, linear RGB [light units x sr].
struct Flux {
  double r = 0, g = 0, b = 0;
  Flux& operator+=(const Flux& o) {
    r += o.r;
    g += o.g;
    b += o.b;
    return *this;
  }
};

struct CausticStatistics {
  /// photons sent (after the cones' overlaps are removed) and stored
  long long photons_traced = 0;
  std::size_t photons_stored = 0;
  /// rays traced by the photons
  std::uint64_t rays = 0;
  int cones = 0;
  /// density estimate radius [scene units]
  double radius = 0;
  /// where the power sent into the cones ended (photon_tracer.h PathEnd): sums to `emitted`;
  /// `roulette` is the net power the roulette removed (+) or added (-), zero on average, with
  /// the variance `roulette_variance` (sum of w (T - w) Phi^2 over the decisions)
  Flux emitted, stored, direct, escaped, absorbed, stopped, cut, roulette, roulette_variance;
  double seconds = 0;
  int threads = 0;
};

class CausticMap {
 public:
  /// No caustics.
  CausticMap() = default;

  /// The photon pass for `scene` at its [caustics] settings (empty when disabled, without
  /// lights or without dielectrics that are not index matched). `threads` 0 = OpenMP default.
  static CausticMap build(const Scene& scene, int threads = 0);

  bool empty() const { return m_map.empty(); }
  /// Caustic irradiance at `p` on a diffuse surface with unit normal `n` facing the viewer.
  Rgb irradiance(const Vec3& p, const Vec3& n) const { return m_map.irradiance(p, n); }
  const PhotonMap& map() const { return m_map; }
  const CausticStatistics& statistics() const { return m_stats; }

 private:
  PhotonMap m_map;
  CausticStatistics m_stats;
};

}  // namespace thaw::render::photon
