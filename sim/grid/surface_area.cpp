#include "sim/grid/surface_area.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace thaw::sim {

SurfaceArea::SurfaceArea(const GridMesh& mesh, const std::vector<double>& m_,
                         const std::vector<char>& exposed_)
    : m_mesh(mesh), m(m_), exposed(exposed_), nx(mesh.nx), ny(mesh.ny), nz(mesh.nz), dx(mesh.dx_m) {
  for (auto* v : {&surface_area, &area_g, &area_w, &area_share, &m_moved})
    v->assign(static_cast<std::size_t>(mesh.n), 0.0);
}

void SurfaceArea::prepare_step(BlockTeam& team, double dt) {
  if (area_stale) midpoint(team, dt);
}

void SurfaceArea::after_step(bool drained, double drained_m3, double dt) {
  // the mean recession speed, drained volume over the heated area: the next step's area is
  // taken half a step ahead (update)
  recession_m_s = 0;
  if (drained) {
    const double area = sum_cells(m_mesh.n, [&](long c) { return surface_area[c]; });
    recession_m_s = area > 0 ? drained_m3 / (area * dt) : 0.0;
  }
  area_stale = drained || area_ahead;
}

/// Material | air area per cell, |grad m| V (mirrored at the grid's walls and the axis), with
/// the share computed in air cells handed to their material neighbours by fraction.
///
/// |grad m| is the mean of two estimates that err in opposite directions on curved surfaces:
/// Youngs' smoothed gradient (central differences averaged across with weights 1, 2, 1: the
/// averaging over differently oriented normals shortens the vector) and the plain central
/// difference (which over-counts the staircase of a tilted surface). On a 3 cm sphere at t = 0
/// the sums are -1.9 % and +2.0 % of 4 pi R^2 on 1.25 mm cells (3D) and -1.3 % and +1.5 % on
/// 0.5 mm cells (axisymmetric); their mean is within 0.07 % in both. Both are exact on a face
/// parallel to the grid. The heated area sets the melt rate directly: Youngs' alone made the 3D
/// sphere melt about 1 % too slowly against the 1D solver (docs/simulate.md).
///
/// The step's areas (on the leader, before the step): the cells' areas from the fractions,
/// scaled to the total area half a step ahead (update).
void SurfaceArea::midpoint(BlockTeam& team, double dt) {
  const double lead = 0.5 * dt * recession_m_s;
  area_ahead = lead > 0;
  double ratio = 1;
  if (area_ahead) {
    update(team, lead);
    ratio = sum_cells(m_mesh.n, [&](long c) { return surface_area[c]; });
  }
  update(team);
  if (!area_ahead) return;
  const double now = sum_cells(m_mesh.n, [&](long c) { return surface_area[c]; });
  ratio = now > 0 ? ratio / now : 1.0;
  team.for_blocks([&](long bl) {
    for (long c = bl * kBlock; c < m_mesh.block_end(bl); ++c) surface_area[c] *= ratio;
  });
}
/// lead_m > 0: the areas of the fractions with the surface moved lead_m along its normal,
/// m - lead_m |grad m|. A step holds its areas while the surface recedes, so step() takes
/// the cells' areas from the fractions as they are, scaled by the ratio of the total area
/// half a step ahead (lead: the last step's mean recession speed) to the total now. From the
/// step's start alone, a shrinking body was heated at its past, larger area: an ablating
/// sphere of radius a ran fast by q dt / (L_v a) relative, first order in the step (0.4-0.7 %
/// over 600 s with 10 s steps at any cell size; measured 0.078 %/s of step against 0.083
/// predicted; docs/validation.md, "Ablation excess"). Tried and rejected: each cell's own
/// melt as its lead (it fed a roughening of the surface at fine cells, +1.5 % at 0.125 mm),
/// and the moved fractions' areas as they are (the offset spreads the gradient one cell
/// deeper, into colder cells, where a convective surface drew more heat: the default hollow
/// sphere broke through 27 s earlier). One ratio for the whole grid: bodies receding at
/// different relative rates keep a first-order remainder in their difference.
///
/// Three or four phases of the team (each writes only its own cells): the moved fractions
/// (lead_m > 0 only); the gradient areas; the material cells' shares (with the air neighbours'
/// areas and the remnant rule below); the areas of the exposed cells (with the shares of their
/// unexposed neighbours).
void SurfaceArea::update(BlockTeam& team, double lead_m) {
  m_geo = m.data();  // the fractions as they are: no copy
  if (lead_m > 0) {
    team.for_blocks([&](long bl) {
      m_mesh.for_cells(bl, [&](long c, int i, int j, int k) {
        m_moved[c] = std::max(0.0, m[c] - lead_m * central_gradient(i, j, k));
      });
    });
    m_geo = m_moved.data();
  }
  team.for_blocks([&](long bl) { m_mesh.for_cells(bl, [&](auto... a) { area_gradient(a...); }); });
  team.for_blocks([&](long bl) { m_mesh.for_cells(bl, [&](auto... a) { area_share_of(a...); }); });
  team.for_blocks([&](long bl) { m_mesh.for_cells(bl, [&](auto... a) { area_final(a...); }); });
}

/// Phase 1: the gradient area of every cell, and for air cells the material around them.
void SurfaceArea::area_gradient(long c, int i, int j, int k) {
  area_g[c] = gradient_area(c, i, j, k);
  double sum = 0;
  if (m[c] == 0)
    m_mesh.for_neighbours(c, i, j, k, [&](long nb) { sum += m[nb] * share_weight(nb); });
  area_w[c] = sum;
}
/// Phase 2: a material cell's own share (reads area_g of air cells only, writes it for
/// material cells only), and what it hands to its exposed neighbours.
void SurfaceArea::area_share_of(long c, int i, int j, int k) {
  area_share[c] = 0;
  if (m[c] == 0) {
    surface_area[c] = 0;
    return;
  }
  double a = area_g[c];
  m_mesh.for_neighbours(c, i, j, k, [&](long nb) {
    if (m[nb] == 0 && area_w[nb] > 0) a += area_g[nb] * (m[c] * share_weight(c)) / area_w[nb];
  });
  area_g[c] = remnant_area(c, i, j, k, a);  // now the material cell'dx own share
  // Only cells open to the outside air take surface heat (their melt drains): a share that
  // the smoothed gradient put one cell deeper goes to its exposed neighbours, evenly (per
  // unit of share_weight: the receiver scales it by its own).
  if (exposed[c] || area_g[c] == 0) return;
  double weights = 0;
  m_mesh.for_neighbours(c, i, j, k, [&](long nb) {
    if (m[nb] > 0 && exposed[nb]) weights += share_weight(nb);
  });
  if (weights > 0) area_share[c] = area_g[c] / weights;
}
/// Phase 3: the exposed cells' areas with the shares handed to them.
void SurfaceArea::area_final(long c, int i, int j, int k) {
  if (m[c] == 0) return;
  if (!exposed[c]) {
    surface_area[c] = area_share[c] > 0 ? 0.0 : area_g[c];  // no exposed neighbour: keep it
    return;
  }
  double a = area_g[c];
  m_mesh.for_neighbours(c, i, j, k, [&](long nb) {
    if (!exposed[nb]) a += area_share[nb] * share_weight(c);
  });
  surface_area[c] = a;
}

/// |grad m| V of cell c (at i, j, k): the mean of Youngs' and the central-difference gradient
/// (above); the fractions beyond the grid's walls mirror the cells inside.
double SurfaceArea::gradient_area(long c, int i, int j, int k) const {
  const bool three = nz > 1;
  const long sy = nx, sz = static_cast<long>(nx) * ny;
  if (i > 0 && i + 1 < nx && j > 0 && j + 1 < ny && (!three || (k > 0 && k + 1 < nz))) {
    auto at = [&](int a, int b, int d) { return m_geo[c + a + sy * b + sz * d]; };
    // Inside the bulk (or the air) every difference is exactly 0, so is the area: the same
    // bits as the formula, at a third of its loads.
    const int kw = three ? 1 : 0;
    bool uniform = true;
    for (int d = -kw; d <= kw && uniform; ++d)
      for (int b = -1; b <= 1 && uniform; ++b)
        for (int a = -1; a <= 1 && uniform; ++a) uniform = at(a, b, d) == m_geo[c];
    return uniform ? 0.0 : gradient_area_at(c, at);
  }
  return gradient_area_at(c, [&](int a, int b, int d) {
    const int ii = std::clamp(i + a, 0, nx - 1), jj = std::clamp(j + b, 0, ny - 1),
              kk = std::clamp(k + d, 0, nz - 1);
    return m_geo[ii + sy * jj + sz * kk];
  });
}
/// |grad m| of the fractions themselves, central differences (walls mirrored) [1/m].
double SurfaceArea::central_gradient(int i, int j, int k) const {
  const long sy = nx, sz = static_cast<long>(nx) * ny;
  auto at = [&](int a, int b, int d) {
    const int ii = std::clamp(i + a, 0, nx - 1), jj = std::clamp(j + b, 0, ny - 1),
              kk = std::clamp(k + d, 0, nz - 1);
    return m[ii + sy * jj + sz * kk];
  };
  const double cx = at(1, 0, 0) - at(-1, 0, 0), cy = at(0, 1, 0) - at(0, -1, 0),
               cz = nz > 1 ? at(0, 0, 1) - at(0, 0, -1) : 0.0;
  return std::sqrt(cx * cx + cy * cy + cz * cz) / (2 * dx);
}
/// The same with at(di, dj, dk) the material fraction of the cell at that offset.
template <class At>
double SurfaceArea::gradient_area_at(long c, At&& at) const {
  const bool three = nz > 1;
  const int kw = three ? 1 : 0;
  // Youngs' gradient ...
  double gx = 0, gy = 0, gz = 0;
  for (int a = -1; a <= 1; ++a)
    for (int b = -kw; b <= kw; ++b) {
      const double w = (2 - std::abs(a)) * (three ? 2 - std::abs(b) : 2);
      gx += w * (at(1, a, b) - at(-1, a, b));
      gy += w * (at(a, 1, b) - at(a, -1, b));
      if (three) gz += w * (at(a, b, 1) - at(a, b, -1));
    }
  const double norm = three ? 16 * 2 * dx : 8 * 2 * dx;
  const double youngs = std::sqrt(gx * gx + gy * gy + gz * gz) / norm;
  // ... and the plain central differences
  const double cx = at(1, 0, 0) - at(-1, 0, 0), cy = at(0, 1, 0) - at(0, -1, 0),
               cz = three ? at(0, 0, 1) - at(0, 0, -1) : 0.0;
  const double central = std::sqrt(cx * cx + cy * cy + cz * cz) / (2 * dx);
  return 0.5 * (youngs + central) * m_mesh.vol[c];
}

/// Remnants thinner than a cell (rods and plates left of a shell's edges, fragments): their
/// cells are less than half full with no bulk behind them, and |grad m| V, which sees a
/// smeared surface, gives them a fraction of their true area (a rod of cross-section 0.3 dx^2
/// has 1.9 dx^2 of surface per cell length, the gradient ~0.6 dx^2), so they lingered for
/// minutes as sub-cell dust. Such a cell gets at least the area of the most compact body of
/// its volume: a sphere in 3D, (36 pi)^(1/3) m^(2/3) dx^2, a torus of round cross-section in
/// (r, y), 2 sqrt(pi m) V / dx; at most 2 V / dx (a plate's two faces).
double SurfaceArea::remnant_area(long c, int i, int j, int k, double a) const {
  if (m[c] >= 0.5 || backed_by_bulk(c, i, j, k)) return a;
  const double compact = nz > 1 ? std::cbrt(36 * std::numbers::pi) * std::pow(m[c], 2.0 / 3)
                                : 2 * std::sqrt(std::numbers::pi * m[c]);
  return std::max(a, std::min(compact, 2.0) * m_mesh.vol[c] / dx);
}

/// A cell at least half full within two cells along any axis: cell c is part of a resolved
/// body's (smeared) surface rather than a sub-cell remnant.
bool SurfaceArea::backed_by_bulk(long c, int i, int j, int k) const {
  const long nxy = static_cast<long>(nx) * ny;
  for (int d = 1; d <= 2; ++d) {
    if ((i - d >= 0 && m[c - d] >= 0.5) || (i + d < nx && m[c + d] >= 0.5)) return true;
    if ((j - d >= 0 && m[c - d * nx] >= 0.5) || (j + d < ny && m[c + d * nx] >= 0.5)) return true;
    if ((k - d >= 0 && m[c - d * nxy] >= 0.5) || (k + d < nz && m[c + d * nxy] >= 0.5)) return true;
  }
  return false;
}

}  // namespace thaw::sim
