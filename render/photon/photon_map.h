#pragma once
// Stored caustic photons and the irradiance density estimate on diffuse surfaces.
// Irradiance at p with unit normal n: E = sum_p Phi_p K(|x_p - p|) over photons within radius r,
// with the Epanechnikov kernel K(d) = 2 / (pi r^2) (1 - d^2 / r^2) (Silverman 1986, "Density
// Estimation", table 3.1, in 2D). K integrates to 1 over the disc, so a uniform photon density
// of flux per area F returns exactly E = F, in the units of the photons' power per area: the
// same units as direct light when Phi = I Omega / N (photon_pass.h). Photons of other surfaces
// are rejected: a photon counts only if its stored normal is within ~25 degrees of n
// (cos > 0.9) and it lies within r / 4 of the tangent plane (a corner, the far side of a thin
// wall, a ball resting on the floor). Photons sit in a hashed uniform grid of cells 2r wide
// (Teschner et al. 2003, "Optimized spatial hashing for collision detection of deformable
// objects"), so a query visits at most 2 x 2 x 2 cells. Built once, immutable, thread-safe to
// query. Knows nothing about lights or tracing.
#include <cstdint>
#include <vector>

#include "render/math/color.h"
#include "render/math/vec3.h"

namespace thaw::render::photon {

struct Photon {
  Vec3 position;
  /// unit geometric normal on the side the photon arrived from
  Vec3 normal;
  /// power [light units x sr, e.g. W for a light in W/sr]
  Rgb power;
};

class PhotonMap {
 public:
  PhotonMap() = default;
  /// `radius` > 0 [scene units].
  PhotonMap(std::vector<Photon> photons, float radius);

  bool empty() const { return m_photons.empty(); }
  std::size_t size() const { return m_photons.size(); }
  float radius() const { return m_radius; }
  /// Photons in grid order.
  const std::vector<Photon>& photons() const { return m_photons; }

  /// Irradiance [power per area] at `p` on a surface with unit normal `n` (facing the side the
  /// light is wanted on).
  Rgb irradiance(const Vec3& p, const Vec3& n) const;

 private:
  std::uint32_t bucket(int ix, int iy, int iz) const;
  std::vector<Photon> m_photons;
  /// photons of bucket k: m_photons[m_start[k] .. m_start[k + 1])
  std::vector<std::uint32_t> m_start;
  std::uint32_t m_mask = 0;
  float m_radius = 0, m_cell = 1;
  Vec3 m_lo, m_hi;  // photons' bounds grown by the radius
};

}  // namespace thaw::render::photon
