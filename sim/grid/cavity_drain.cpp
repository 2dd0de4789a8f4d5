#include "sim/grid/cavity_drain.h"

#include <algorithm>

namespace thaw::sim {

namespace {
/// Ice left in a drained cell below this fraction is removed with it: at T_m its enthalpy is
/// zero, so the energy balance is untouched; the volume is booked as removed_ice_m3.
constexpr double kRemnantFraction = 1e-3;
}  // namespace

CavityDrain::CavityDrain(const GridMesh& mesh, const PhaseRelation& phase, CellState& cells,
                         bool drain)
    : m_mesh(mesh), m_phase(phase), m_cells(cells), m_drain(drain) {
  for (auto* v : {&open_prev, &enclosed_prev, &m_exposed, &open_now, &outside_now})
    v->assign(static_cast<std::size_t>(mesh.n), 0);
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

void CavityDrain::fill_outside() {
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
      if (open_now[nb] && !outside_now[nb]) {
        outside_now[nb] = 1;
        queue.push_back(nb);
      }
    });
}

void CavityDrain::remember_openness(long c) {
  enclosed_prev[c] = open_now[c] && !outside_now[c];
  open_prev[c] = open_now[c];
}

void CavityDrain::classify(BlockTeam& team) {
  flood(team);
  team.for_blocks([&](long bl) {
    for (long c = bl * kBlock; c < m_mesh.block_end(bl); ++c) remember_openness(c);
  });
}

long CavityDrain::detect_break_through() {
  if (m_broke_through) return -1;
  const long n = m_mesh.n;
  long first = -1, fallback = -1;
  for (long c = 0; c < n && fallback < 0; ++c)
    if (outside_now[c] && enclosed_prev[c]) fallback = c;
  if (fallback < 0) return -1;
  for (long c = 0; c < n && first < 0; ++c) {
    if (!outside_now[c] || open_prev[c]) continue;
    bool next_to_cavity = false;
    m_mesh.for_neighbours(c, [&](long nb) { next_to_cavity |= enclosed_prev[nb] != 0; });
    if (next_to_cavity) first = c;
  }
  m_broke_through = true;
  return first >= 0 ? first : fallback;
}

void CavityDrain::drain_cell(long c, DrainTally& b) {
  std::vector<double>& m = m_cells.m;
  std::vector<double>& H = m_cells.H;
  const std::vector<double>& vol = m_mesh.vol;
  if (!(m_drain && m_exposed[c] && m[c] > 0 && H[c] > 0)) return;
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
  b.enclosed += m_exposed[c] ? 0.0 : m[c] * m_mesh.vol[c] * m_phase.liquid(H[c]);
  const double wet = m_exposed[c] ? 0.0 : m[c] * m_phase.liquid(H[c]);
  if (wet > b.wettest) {
    b.wettest = wet;
    b.wettest_cell = c;
  }
}

double CavityDrain::enclosed_liquid_volume() const {
  const std::vector<double>& m = m_cells.m;
  const std::vector<double>& H = m_cells.H;
  return sum_cells(m_mesh.n, [&](long c) {
    return m_exposed[c] ? 0.0 : m[c] * m_mesh.vol[c] * m_phase.liquid(H[c]);
  });
}

}  // namespace thaw::sim
