#pragma once
// Stored caustic photons and the irradiance density estimate on diffuse surfaces.
// Irradiance at p with unit normal n: E = sum_p Phi_p K_p(|x_p - p|), each photon spread over a
// disc of its own radius r_p with the Epanechnikov kernel K_p(d) = 2 / (pi r_p^2) (1 - d^2 / r_p^2)
// (Silverman 1986, "Density Estimation", table 3.1, in 2D; the "scatter" form of a density
// estimate). Every K_p integrates to 1, so photons keep their power exactly, and a uniform photon
// density of flux per area F returns exactly E = F, in the units of the photons' power per area:
// the same units as direct light when Phi = I Omega / N (caustic_map.h).
// Radius: r_p = r where at least `photons_per_disc` (K) photons share the photon's grid cell (2r
// wide: about the count within r, found in O(1)) (the focused, well sampled caustic keeps the
// sharp kernel); where fewer, n, do (the faint light
// reflected off the ice and the halo around the caustic, carried by few photons), r_p grows to
// the smallest 2^c r with 4^c n >= K, at most 8r, so that sparse photons become a smooth glow
// instead of grain (the adaptive-kernel idea of Silverman sec. 5.3, the pilot count taken per
// cell). The price: a caustic's edges, where the cells are partly empty, get 2r.
// Photons of other surfaces are rejected: a photon counts only if its stored normal is within
// ~25 degrees of n (cos > 0.9) and it lies within r_p / 4 of the tangent plane (a corner, the far
// side of a thin wall, a ball resting on the floor). Each radius class (r, 2r, 4r, 8r) sits in a
// hashed uniform grid of cells 2 r_class wide (Teschner et al. 2003, "Optimized spatial hashing
// for collision detection of deformable objects"), so a query visits at most 2 x 2 x 2 cells
// per class. Built once, immutable, thread-safe to query. Knows nothing about lights or tracing.
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
  /// Radius classes r, 2r, 4r, 8r.
  static constexpr int kClasses = 4;

  PhotonMap() = default;
  /// `radius` > 0 [scene units]; photons among at least `photons_per_disc` (>= 1) keep it,
  /// sparser ones get wider kernels (see above).
  PhotonMap(const std::vector<Photon>& photons, float radius, double photons_per_disc);

  bool empty() const { return size() == 0; }
  std::size_t size() const;
  /// the base radius r
  float radius() const { return m_radius; }
  /// Photons of radius class c (radius r 2^c), in a fixed order.
  const std::vector<Photon>& photons(int radius_class) const {
    return m_grids[std::size_t(radius_class)].photons;
  }

  /// Irradiance [power per area] at `p` on a surface with unit normal `n` (facing the side the
  /// light is wanted on).
  Rgb irradiance(const Vec3& p, const Vec3& n) const;

 private:
  /// One radius class: photons in a hashed grid.
  struct Grid {
    std::vector<Photon> photons;
    /// photons of bucket k: photons[start[k] .. start[k + 1])
    std::vector<std::uint32_t> start;
    std::uint32_t mask = 0;
    float radius = 0, cell = 1;
    Vec3 lo, hi;  // photons' bounds grown by the radius

    Grid() = default;
    Grid(std::vector<Photon> photons, float radius);
    std::uint32_t bucket(int ix, int iy, int iz) const;
    /// Calls f(photon, offset from p, squared distance) for the photons within `radius` of p
    /// until f returns false.
    template <class F>
    void for_each_near(const Vec3& p, F&& f) const;
  };
  std::vector<Grid> m_grids;
  float m_radius = 0;
};

}  // namespace thaw::render::photon
