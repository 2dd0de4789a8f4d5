#pragma once
// Caustics: light from the point lights that reaches diffuse surfaces through dielectrics
// (refracted, reflected, absorbed and dispersed), found by one photon pass per frame and
// returned as irradiance E for the integrator to add at a diffuse hit as albedo * kd * E, beside
// the direct light (which the dielectrics shadow: nothing is counted twice, photon_tracer.h).
//
// The pass: photons are aimed from each light (point and sphere lights, light_cone.h) into the
// cones of the dielectric objects' bounding spheres, N_k of them into cone k, their directions,
// wavelengths and emission points the points of a scrambled Halton sequence (low_discrepancy.h:
// the same points every frame and for any thread count, so frames do not flicker), traced by
// photon_tracer.h and stored on diffuse surfaces into one photon_map.h per target object, each
// with its own radius (a 3 cm ice shell's focus needs a finer kernel than an 11 cm puddle's
// even light). Photon power (RGB):
//   falloff = "inverse_square": Phi = I Omega_k / N_k, so that the density estimate returns
//     E = I cos(theta) / d^2 exactly as the direct light does (a sphere light of radius a and
//     radiance L has I = L pi a^2: it gives that E too);
//   falloff = "none" (POV-Ray): direct light is E = I cos(theta) at any distance, which no
//     photon flux can reproduce everywhere; photons carry Phi = I D_k^2 Omega_k / N_k, D_k the
//     distance from the light to the target's centre, so the caustic has the brightness the
//     direct light has at the object's distance (and then falls off as 1/d^2 beyond, as light
//     does).
// In spectral scenes with a dispersive or absorbing medium a photon carries one wavelength (Halton
// dimension 2, drawn with the visible density of the film) and its power is the sRGB of the light's
// uplifted spectrum at that wavelength: Phi_rgb = scale * M_xyz->srgb (S(lambda) cmf(lambda)) /
// p(lambda), which averages to the light's colour (a white light's photons sum to white). Otherwise
// photons carry the light's RGB colour (photons_carry_wavelengths). Automatic settings
// (docs/render.md "Caustics"): N = 150k photons in all; cone k gets N_k in proportion to
// sqrt(power_k) (between equal shares, which would blur large targets, and shares in proportion to
// power, which give every target the same radius, too coarse for a small shell beside a large
// puddle); target t's radius is r_t = min_k R_k sqrt(K / N_k) over its cones (R_k the cone's aiming
// radius): where the light is not focused, K photons fall in the kernel's disc. Photons are traced
// in fixed chunks in parallel (OpenMP) and stored in photon index order, so the maps do not depend
// on the thread count. Nothing throws inside the parallel loop.
#include <atomic>
#include <cstdint>
#include <vector>

#include "render/math/color.h"
#include "render/photon/photon_map.h"
#include "render/scene/scene.h"

namespace thaw::render::photon {

/// Automatic photon count (all lights and targets together) when [caustics] photons is not set.
inline constexpr long long kDefaultPhotons = 150000;
/// Automatic radius: photons expected in the kernel's disc where the light is not focused.
inline constexpr double kPhotonsPerDisc = 32.0;
/// Photons a kernel gathers where they are sparser than that (PhotonMap's adaptive radius), so
/// evenly lit areas (the floor under the puddle) are smooth. Measured on a 22 cm water slab
/// (150k photons, photon noise = RMS residual against a 1 cm box mean): 5.8 % at 32, 3.4 % at
/// 64, 2.2 % at 128, for 1.5, 2.4 and 4.9 us per query (1 thread, loaded machine); the focused
/// caustic, denser, keeps the base radius. 64 left the default film's puddle floor (lit by photons
/// only) visibly cloudy; 256 halves the noise (1/sqrt K) for +10 % frame time (docs/render.md).
inline constexpr double kSmoothPhotons = 256.0;

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

/// One target object's photons.
struct TargetStatistics {
  /// the target's bounding sphere
  Vec3 center;
  double bounding_radius = 0;
  /// photons aimed at it (all lights) and stored in its map
  long long photons_traced = 0;
  std::size_t photons_stored = 0;
  /// its density estimate's radius [scene units]
  double radius = 0;
};

struct CausticStatistics {
  /// photons sent (after the cones' overlaps are removed) and stored
  long long photons_traced = 0;
  std::size_t photons_stored = 0;
  /// rays traced by the photons
  std::uint64_t rays = 0;
  int cones = 0;
  std::vector<TargetStatistics> targets;
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
  /// `cancel` set (RenderOptions::cancel): the remaining photons are skipped, the map is partial.
  static CausticMap build(const Scene& scene, int threads = 0,
                          const std::atomic<bool>* cancel = nullptr);

  bool empty() const {
    for (const PhotonMap& m : m_maps)
      if (!m.empty()) return false;
    return true;
  }
  /// Caustic irradiance at `p` on a diffuse surface with unit normal `n` facing the viewer:
  /// the sum over the targets' maps.
  Rgb irradiance(const Vec3& p, const Vec3& n) const {
    Rgb e;
    for (const PhotonMap& m : m_maps) e += m.irradiance(p, n);
    return e;
  }
  /// One map per target (CausticStatistics::targets, same order).
  const std::vector<PhotonMap>& maps() const { return m_maps; }
  const CausticStatistics& statistics() const { return m_stats; }

 private:
  std::vector<PhotonMap> m_maps;
  CausticStatistics m_stats;
};

}  // namespace thaw::render::photon
