#pragma once
// Follows one photon from a light through the scene's dielectric interfaces, exactly as the
// camera rays of the Whitted integrator cross them: media tracked by interface labels, eta =
// n_to / n_from at the photon's wavelength (n_d in RGB scenes), exact Fresnel reflectance
// (render/material/fresnel.h), Snell refraction, total internal reflection, and Beer-Lambert
// absorption exp(-alpha(lambda) d) along every segment inside an absorbing medium (in RGB scenes
// exp(-alpha_c d) per channel with the integrator's coefficients, media::Absorption::srgb_per_m,
// carried as the events' tint: photons keep the light's colour and no wavelength noise). At each
// interface BOTH branches are followed, the reflected one with weight R and the refracted one with
// 1 - R (splitting: no branch-choice noise on the light that carries the caustic). Branches lighter
// than `roulette_weight` (a fraction of the photon's power) are decided by Russian roulette
// instead: they go on with probability w / roulette_weight carrying roulette_weight, else end.
// Splitting everything down to min_weight traced 10.8 rays per S1 photon, mostly for the 2-4 %
// Fresnel reflections; roulette on them brings it to ~5.5 at no bias. The decisions are
// low-discrepancy too (Halton dimensions 5-7 of the photon's index for its first three decisions, a
// fixed hash after; 0-4 are the direction, wavelength and emission point), so they are the same in
// every frame and stratified across photons. Without roulette (roulette_weight = 0) branches are
// split down to the scene's min_weight like camera rays. Accounting is exact either way: a branch
// lost to roulette is an event of weight +w, a survivor one of weight -(roulette_weight - w) (the
// power it gains), so a photon's events always sum to its weight (the flux-conservation test), and
// the roulette events sum to zero on average. Index-matched interfaces (SceneObject::index_matched)
// are crossed straight, without a split and without using a level of max_depth: they are invisible.
// A path ends on an opaque surface, in the sky, fully absorbed or cut. It is a CAUSTIC photon
// if, before reaching a diffuse (matte or phong) surface, it met an interface that is not index
// matched: shadow rays are blocked by exactly those interfaces (Scene::occluded), so stored
// photons and direct light never count the same light twice.
// Knows nothing about lights' power, colour or the density estimate.
#include <cstdint>
#include <vector>

#include "render/math/ray.h"
#include "render/scene/scene.h"

namespace thaw::render::photon {

/// How a branch of a photon path ended.
enum class PathEnd : std::uint8_t {
  /// caustic photon on a diffuse surface: stored
  stored,
  /// reached a diffuse surface or the sky without meeting a non-matched interface (direct light)
  direct,
  /// left the scene after meeting a non-matched interface
  escaped,
  /// Beer-Lambert absorption inside a medium
  absorbed,
  /// hit a metal or emissive surface (not followed)
  stopped,
  /// below min_weight or beyond max_depth
  cut,
  /// Russian roulette: +w for a branch ended, -(gain) for a survivor (sums to ~0)
  roulette,
};

struct PathEvent {
  PathEnd end = PathEnd::cut;
  /// stored/direct on a surface: the hit point; escaped/direct to the sky: the last ray's origin
  Vec3 position;
  /// stored/direct on a surface: unit geometric normal on the side the photon came from;
  /// escaped: the direction the photon left in
  Vec3 normal;
  /// fraction of the photon's power ending this way
  float weight = 0;
  /// RGB scenes with absorbing media: the per-channel Beer-Lambert transmittance the branch kept
  /// (for an `absorbed` event: the share it lost on that segment); the event carries
  /// power * weight * tint. (1, 1, 1) otherwise.
  Rgb tint{1.0f, 1.0f, 1.0f};
};

/// Reusable buffer for one photon's events (keeps its capacity between photons).
using PathEvents = std::vector<PathEvent>;

/// Whether photons need a wavelength: spectral scenes with a dispersive or absorbing medium.
/// Otherwise every wavelength takes the same path with the same losses, so photons carry the
/// light's RGB colour and use n_d (exact, no wavelength-sampling noise), in spectral scenes too.
bool photons_carry_wavelengths(const Scene& scene);

/// The medium containing point `p` of `scene` (found by following a ray upward through the
/// interfaces, past opaque objects); the camera's medium when no interface encloses it.
std::uint32_t medium_at(const Scene& scene, const Vec3& p);

class PhotonTracer {
 public:
  /// Precomputes n(lambda) and alpha(lambda) of every medium at 1 nm steps when photons carry
  /// wavelengths (photons_carry_wavelengths), else n_d. `roulette_weight` in [0, 1): see above (0 =
  /// split down to min_weight).
  explicit PhotonTracer(const Scene& scene, float roulette_weight = 0.0f);

  /// Traces a photon of unit weight along `ray` (unit direction) starting in `medium`, at
  /// wavelength `lambda_nm` (ignored in RGB scenes); replaces `events` by how it ended (their
  /// weights sum to 1). `photon_index` selects the roulette decisions. Allocates (and so may
  /// throw std::bad_alloc) only when a path has more events than `events` has capacity for.
  /// Returns the rays traced.
  std::uint32_t trace(const Ray& ray, std::uint32_t medium, double lambda_nm, PathEvents& events,
                      std::uint64_t photon_index = 0) const;

  /// The medium containing point `p` (photon::medium_at).
  std::uint32_t medium_at(const Vec3& p) const;

  /// Index of refraction of medium `m` at `lambda_nm` as the tracer uses it.
  float ior(std::uint32_t m, double lambda_nm) const;

 private:
  float absorption_per_m(std::uint32_t m, double lambda_nm) const;
  const Scene& m_scene;
  bool m_spectral;
  int m_max_depth;
  float m_min_weight, m_roulette_weight;
  /// per medium: n at 380, 381, ..., 780 nm (one entry in RGB scenes)
  std::vector<std::vector<float>> m_ior;
  /// per medium: alpha [1/m] at 380, ..., 780 nm, empty when it does not absorb
  std::vector<std::vector<float>> m_alpha;
  /// RGB scenes, per medium: alpha [1/m] per linear-sRGB channel (black: no absorption)
  std::vector<Rgb> m_alpha_rgb;
};

}  // namespace thaw::render::photon
