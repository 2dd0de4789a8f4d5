#pragma once
// Stored caustic photons and the irradiance density estimate on diffuse surfaces.
// Irradiance at p with unit normal n: E = sum_p Phi_p K_p(|x_p - p|), each photon spread over a
// disc of its own radius r_p with the Epanechnikov kernel K_p(d) = 2 / (pi r_p^2) (1 - d^2 / r_p^2)
// (Silverman 1986, "Density Estimation", table 3.1, in 2D; the "scatter" form of a density
// estimate). Every K_p integrates to 1, so photons keep their power exactly, and a uniform photon
// density of flux per area F returns exactly E = F, in the units of the photons' power per area:
// the same units as direct light when Phi = I Omega / N (caustic_map.h).
// Radius: each photon's r_p = r sqrt(K / n_r), clamped to [r, 8r], where n_r estimates the photons
// within r of it from the count of the 8 grid cells (2r wide) around it (O(1)) and K =
// `photons_per_disc`: the focused, well sampled caustic keeps the sharp kernel r, while the faint
// light reflected off the ice and the halo around the caustic, carried by few photons, is spread
// into a smooth glow instead of grain (the adaptive-kernel idea of Silverman sec. 5.3, the pilot
// density taken per cell). r_p is continuous in the count, so a uniform region (cell counts
// scattering around K) keeps radii within a few percent of r instead of a cell pattern of two
// kernels. The price: a caustic's edges, where cells are partly empty, get a wider kernel.
// Photons of other surfaces are rejected: a photon counts only if its stored normal is within
// ~25 degrees of n (cos > 0.9) and it lies within r_p / 4 of the tangent plane (a corner, the far
// side of a thin wall, a ball resting on the floor). Photons whose r_p is at most r, 1.41r, 2r,
// ..., 8r sit in seven hashed uniform grids of cells 2 r_class wide (Teschner et al. 2003,
// "Optimized spatial hashing for collision detection of deformable objects"), so a query visits at
// most 2 x 2 x 2 cells per class. Built once, immutable, thread-safe to query. Knows nothing about
// lights or tracing.
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
  /// 1 / r_p^2 of its kernel [1 / scene units^2] (set by PhotonMap)
  float inv_radius2 = 0;
};

class PhotonMap {
 public:
  /// Grids for kernel radii up to r 2^(c/2), c = 0..6 (r .. 8r in steps of sqrt 2).
  static constexpr int kClasses = 7;

  PhotonMap() = default;
  /// `radius` > 0 [scene units]; photons among at least `photons_per_disc` (>= 1) keep it,
  /// sparser ones get wider kernels (see above).
  PhotonMap(const std::vector<Photon>& photons, float radius, double photons_per_disc);

  bool empty() const { return size() == 0; }
  std::size_t size() const;
  /// the base radius r
  float radius() const { return m_radius; }
  /// Photons whose kernel radius is in (r 2^((c-1)/2), r 2^(c/2)] (c = 0: exactly r), in a
  /// fixed order.
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
    /// Photons in the 2 x 2 x 2 cells a query at p visits.
    std::uint32_t count_near(const Vec3& p) const;
    /// Calls f(photon, offset from p, squared distance) for the photons within `radius` of p
    /// until f returns false.
    template <class F>
    void for_each_near(const Vec3& p, F&& f) const;
  };
  std::vector<Grid> m_grids;
  float m_radius = 0;
};

}  // namespace thaw::render::photon
