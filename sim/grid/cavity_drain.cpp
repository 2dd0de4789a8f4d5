#include "sim/grid/cavity_drain.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace thaw::sim {

namespace {
/// Ice left in a drained cell below this fraction is removed with it: at T_m its enthalpy is
/// zero, so the energy balance is untouched; the volume is booked as removed_ice_m3.
constexpr double kRemnantFraction = 1e-3;
/// The level of a sealed cavity: no free surface.
constexpr double kSealed = std::numeric_limits<double>::infinity();
}  // namespace

CavityDrain::CavityDrain(const GridMesh& mesh, const PhaseRelation& phase, CellState& cells,
                         bool drain)
    : m_mesh(mesh), m_phase(phase), m_cells(cells), m_drain(drain) {
  for (auto* v : {&m_exposed, &open_now, &outside_now, &m_cavity, &cavity_prev})
    v->assign(static_cast<std::size_t>(mesh.n), 0);
  for (auto* v : {&m_level, &level_prev}) v->assign(static_cast<std::size_t>(mesh.n), kSealed);
  queue.reserve(static_cast<std::size_t>(mesh.n));
}

/// Flood fill from the air at the grid's border through cells less than half ice: `open_now`
/// (cell less than half ice), `outside_now` (connected), `exposed` = outside or next to it.
/// The fill itself is serial (on the leader; a breadth-first search over the open cells).
void CavityDrain::flood(BlockTeam& team) {
  team.for_blocks([&](long bl) {
    for (long c = bl * kBlock; c < m_mesh.block_end(bl); ++c) mark_open(c);
  });
  team.serial([&] { fill_outside(); });
  team.for_blocks([&](long bl) { m_mesh.for_cells(bl, [&](auto... a) { exposure(a...); }); });
}

void CavityDrain::exposure(long c, int i, int j, int k) {
  m_exposed[c] = outside_now[c];
  if (!outside_now[c])
    m_mesh.for_neighbours(c, i, j, k, [&](long nb) { m_exposed[c] |= outside_now[nb]; });
}

void CavityDrain::flood_outside() {
  const std::vector<double>& m = m_cells.m;
  const int nx = m_mesh.nx, ny = m_mesh.ny, nz = m_mesh.nz;
  const bool axisymmetric = m_mesh.axisymmetric;
  const long nxy = m_mesh.nxy();
  std::fill(outside_now.begin(), outside_now.end(), 0);
  queue.clear();
  auto seed = [&](long c) {
    if (m[c] == 0 && !outside_now[c]) {
      outside_now[c] = 1;
      queue.push_back(c);
    }
  };
  // the border cells: the faces j = 0, ny - 1 and i = nx - 1, and (3D) i = 0, k = 0, nz - 1
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j) {
      const long row = j * static_cast<long>(nx) + k * nxy;
      const bool face = j == 0 || j == ny - 1 || (!axisymmetric && (k == 0 || k == nz - 1));
      if (face) {
        for (int i = 0; i < nx; ++i) seed(row + i);
      } else {
        if (!axisymmetric) seed(row);
        seed(row + nx - 1);
      }
    }
  for (std::size_t head = 0; head < queue.size(); ++head)
    m_mesh.for_neighbours(queue[head], [&](long nb) {
      if (open_now[nb] && !m_cavity[nb] && !outside_now[nb]) {
        outside_now[nb] = 1;
        queue.push_back(nb);
      }
    });
}

/// The cavities' liquid as it is now: from every cavity cell that is still at least half liquid,
/// through such cells that are not outside. So a cavity takes in the wall cells its water
/// melts into (and the melt the air makes in a wall cell it shares with the cavity: the wall is
/// in that cell, the split of its liquid unknown), and lets go of cells that froze.
void CavityDrain::grow_cavities() {
  const std::vector<double>& m = m_cells.m;
  const std::vector<double>& H = m_cells.H;
  // the front is where the liquid fraction crosses one half (enthalpy_solver.h): a cell at
  // T_m with a trace of liquid (the whole wall reaches T_m before it melts) is still wall; an
  // opened cavity holds nothing in cells above its level
  auto wet = [&](long c, double level) {
    return m[c] > 0 && 2 * H[c] >= m_phase.latent && !outside_now[c] && bottom(c) < level;
  };
  cavity_prev.swap(m_cavity);
  level_prev.swap(m_level);
  std::fill(m_cavity.begin(), m_cavity.end(), 0);
  std::fill(m_level.begin(), m_level.end(), kSealed);
  queue.clear();
  for (long c = 0; c < m_mesh.n; ++c)
    if (cavity_prev[c] && wet(c, level_prev[c])) {
      m_cavity[c] = 1;
      m_level[c] = level_prev[c];
      queue.push_back(c);
    }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const double level = m_level[queue[head]];
    m_mesh.for_neighbours(queue[head], [&](long nb) {
      if (!m_cavity[nb] && wet(nb, level)) {
        m_cavity[nb] = 1;
        m_level[nb] = level;
        queue.push_back(nb);
      }
    });
  }
}

double CavityDrain::opening_height(long c, long nb) const {
  const double yc = m_mesh.centre(c)[1], yn = m_mesh.centre(nb)[1];
  if (yn > yc + 0.5 * m_mesh.dx_m) return yc + 0.5 * m_mesh.dx_m;  // a hole in the roof
  if (yn < yc - 0.5 * m_mesh.dx_m) return yc - 0.5 * m_mesh.dx_m;  // in the floor
  return yc;
}

double CavityDrain::below(long c, double level) const {
  return std::clamp((level - bottom(c)) / m_mesh.dx_m, 0.0, 1.0);
}

bool CavityDrain::ice_free(long c) const {
  return ice_fraction(c) < kRemnantFraction;
}

/// A cavity opens where one of its cells and an outside neighbour both hold no ice: the wall's
/// thickness reconstructed along the line through the two cells, dx (f_ice(a) + f_ice(b)), is
/// zero there (it is the height function of the wall across that face: a wall whose normal is
/// within 45 degrees of the face normal lies in those two cells). A cell less than half ice
/// next to the outside is not enough: the wall can still be most of two cells thick (the old
/// rule opened the default hollow sphere's 3D shell at 1940 s, with 1.6 mm of wall left on
/// 1.25 mm cells, against 2310 s in 1D). The opened cavity's cells stop being a cavity; the
/// outside is flooded again through them.
void CavityDrain::open_cavities() {
  bool opened = false;
  for (long c = 0; c < m_mesh.n; ++c) {
    if (!m_cavity[c] || !ice_free(c)) continue;
    long gap = -1;
    double height = m_level[c];
    m_mesh.for_neighbours(c, [&](long nb) {
      if (!outside_now[nb] || !ice_free(nb)) return;
      const double h = opening_height(c, nb);
      if (h < height) {  // below the free surface (a sealed cavity's is at infinity)
        gap = nb;
        height = h;
      }
    });
    if (gap < 0) continue;
    const auto a = m_mesh.centre(c), b = m_mesh.centre(gap);
    const std::array<double, 3> where{0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]),
                                      0.5 * (a[2] + b[2])};
    if (m_level[c] == kSealed) {
      if (!m_broke_through && !m_opening) m_opening = where;
    } else {
      m_level_drops.push_back({where, height});
    }
    // the whole cavity this cell belongs to takes the new level
    const double old_level = m_level[c];
    queue.clear();
    m_level[c] = height;
    queue.push_back(c);
    for (std::size_t head = 0; head < queue.size(); ++head)
      m_mesh.for_neighbours(queue[head], [&](long nb) {
        if (m_cavity[nb] && m_level[nb] == old_level) {
          m_level[nb] = height;
          queue.push_back(nb);
        }
      });
    opened = true;
  }
  if (!opened) return;
  // cells left above the level hold no water: they leave the cavity (and drain)
  for (long c = 0; c < m_mesh.n; ++c)
    if (m_cavity[c] && bottom(c) >= m_level[c]) m_cavity[c] = 0;
  flood_outside();
}

void CavityDrain::fill_outside() {
  flood_outside();
  grow_cavities();
  open_cavities();
}

void CavityDrain::classify(BlockTeam& team) {
  flood(team);
  // The initial cavities: liquid enclosed by cells at least half ice, with the wall cells
  // their liquid wets.
  team.serial([&] {
    const std::vector<double>& m = m_cells.m;
    const std::vector<double>& H = m_cells.H;
    for (long c = 0; c < m_mesh.n; ++c)
      m_cavity[c] = open_now[c] && !outside_now[c] && m[c] > 0 && 2 * H[c] >= m_phase.latent;
    grow_cavities();
  });
}

std::vector<std::pair<std::array<double, 3>, double>> CavityDrain::take_level_drops() {
  std::vector<std::pair<std::array<double, 3>, double>> out;
  out.swap(m_level_drops);
  return out;
}

double CavityDrain::water_level_m() const {
  double level = kSealed;
  for (long c = 0; c < m_mesh.n; ++c)
    if (m_cavity[c] && m_level[c] != kSealed) level = std::min(level, m_level[c]);
  return level;
}

double CavityDrain::held_water_volume() const {
  const std::vector<double>& m = m_cells.m;
  const std::vector<double>& H = m_cells.H;
  return sum_cells(m_mesh.n, [&](long c) {
    return m_cavity[c] && m_level[c] != kSealed ? m[c] * m_mesh.vol[c] * m_phase.liquid(H[c]) : 0.0;
  });
}

std::optional<std::array<double, 3>> CavityDrain::detect_break_through() {
  if (m_broke_through || !m_opening) return std::nullopt;
  m_broke_through = true;
  return m_opening;
}

void CavityDrain::drain_cell(long c, DrainTally& b) {
  std::vector<double>& m = m_cells.m;
  std::vector<double>& H = m_cells.H;
  const std::vector<double>& vol = m_mesh.vol;
  if (!m_drain || m[c] <= 0 || H[c] <= 0) return;
  if (m_cavity[c]) {
    if (m_level[c] == kSealed) return;
    // an opened cavity's cell keeps its liquid up to the level: that share of its room not
    // taken by ice; the excess drains with its enthalpy per unit volume of liquid, L_v at T_m
    // (a melting cell) or H (water above T_m)
    const double f = m_phase.liquid(H[c]);
    const double room = below(c, m_level[c]) * (1 - m[c] * (1 - f));
    const double excess = m[c] * f - room;
    if (excess <= 0) return;
    const double per_volume = std::max(H[c], m_phase.latent);
    const double e = excess * vol[c] * per_volume;
    b.drained += e;
    if (e > b.most_drained) {
      b.most_drained = e;
      b.most_drained_cell = c;
    }
    const double left = m[c] - excess;
    H[c] = left > 0 ? (m[c] * H[c] - excess * per_volume) / left : 0.0;
    m[c] = left > 0 ? left : 0.0;
    return;
  }
  if (!m_exposed[c]) return;
  const double e = m[c] * vol[c] * H[c];
  b.drained += e;
  if (e > b.most_drained) {
    b.most_drained = e;
    b.most_drained_cell = c;
  }
  const double f = m_phase.liquid(H[c]);
  m[c] = f >= 1 ? 0.0 : m[c] * (1 - f);
  if (m[c] < kRemnantFraction) {
    b.removed += m[c] * vol[c];
    m[c] = 0;
  }
  H[c] = 0;
}

void CavityDrain::add_enclosed(long c, EnclosedTally& b) const {
  const std::vector<double>& m = m_cells.m;
  const std::vector<double>& H = m_cells.H;
  b.enclosed += held(c) ? m[c] * m_mesh.vol[c] * m_phase.liquid(H[c]) : 0.0;
  const double wet = held(c) ? m[c] * m_phase.liquid(H[c]) : 0.0;
  if (wet > b.wettest) {
    b.wettest = wet;
    b.wettest_cell = c;
  }
}

double CavityDrain::enclosed_liquid_volume() const {
  const std::vector<double>& m = m_cells.m;
  const std::vector<double>& H = m_cells.H;
  return sum_cells(m_mesh.n, [&](long c) {
    return held(c) ? m[c] * m_mesh.vol[c] * m_phase.liquid(H[c]) : 0.0;
  });
}

}  // namespace thaw::sim
