#pragma once
// Cavities and drainage of the grid solver: which cells are open to the outside air (a flood
// fill from the grid's air border through cells less than half ice that are not held in a
// cavity), which are exposed (outside or next to it), the melt that drains from exposed cells
// outside the cavities (its enthalpy booked as drained; ice remnants below kRemnantFraction go
// with it), the liquid still enclosed, and the moment a cavity joins the outside
// (break-through: where the wall between them is gone, not where a cell is less than half
// ice). Writes m and H of drained cells and its own arrays. Knows nothing of heat conduction,
// Newton or step sizes.
//
// An opened cavity holds its water as a cup (issue 25 item 1): water drains only through
// openings below its free surface. Its level is the height of its lowest opening (gravity along
// -y); the cavity's cells keep what lies below the level (a cell cut by the level keeps that
// share of its room not taken by ice: a flat, hydrostatic surface to the sub-cell) and go on
// exchanging heat as before; the rest drains. The cup is always full to its lowest opening, so
// melt made above the level would spill there anyway and drains as outside melt. A hole below
// the level (the wall gone between a held cell and an outside cell, as for break-through)
// lowers it: a `water_level_drop`.
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "sim/grid/block_team.h"
#include "sim/grid/cell_state.h"
#include "sim/grid/grid_mesh.h"
#include "sim/grid/phase_relation.h"

namespace thaw::sim {

/// One block's share of what drained in a step (added up by the stepper in block order).
struct DrainTally {
  double drained = 0;           ///< drained enthalpy [J]
  double most_drained = 0;      ///< the most any one cell drained [J]
  double removed = 0;           ///< ice remnants removed with the melt [m^3]
  long most_drained_cell = -1;  ///< that cell (first among equals), -1 if none drained
};

/// One block's share of the enclosed liquid (not exposed to the outside).
struct EnclosedTally {
  double enclosed = 0;  ///< enclosed liquid volume [m^3]
  double wettest = 0;   ///< the largest enclosed liquid fraction of a cell
  long wettest_cell = -1;
};

class CavityDrain {
 public:
  /// `drain`: melt drains away where it touches the outside air (GridProblem::drain).
  CavityDrain(const GridMesh& mesh, const PhaseRelation& phase, CellState& cells, bool drain);

  /// exposed[c]: cell c is outside, or next to a cell outside (it takes the surface heat).
  const std::vector<char>& exposed() const { return m_exposed; }
  /// cavity[c]: cell c holds liquid of a cavity whose wall still stands: it is never outside
  /// and does not drain, even next to the outside (the wall is then inside it or its
  /// neighbour).
  const std::vector<char>& cavity() const { return m_cavity; }
  /// Openness, exposure and the cavities from the current state (the constructor's start: the
  /// initial cavities are the liquid enclosed by cells at least half ice, with the wall cells
  /// it wets).
  void classify(BlockTeam& team);
  /// open_now[c] from the cell's ice fraction (less than half ice).
  void mark_open(long c) { open_now[c] = ice_fraction(c) < 0.5; }
  /// outside_now from open_now: a breadth-first flood from the grid's border through open cells
  /// outside the cavities; then the cavities (grown into the wall cells their liquid reached,
  /// shrunk where it froze) and their openings: a cavity whose wall is gone somewhere joins
  /// the outside (serial).
  void fill_outside();
  /// exposed[c] from outside_now.
  void exposure(long c, int i, int j, int k);
  /// After fill_outside: the first break-through, where the first cavity opened (the middle of
  /// the face between its ice-free cell and the ice-free outside cell), once; nothing if no
  /// cavity has opened or the first one was already reported. Serial.
  std::optional<std::array<double, 3>> detect_break_through();
  bool broke_through() const { return m_broke_through; }
  /// After fill_outside: the level drops of opened cavities since the last call (where the
  /// new lowest opening is, and the new level [m]). Serial.
  std::vector<std::pair<std::array<double, 3>, double>> take_level_drops();
  /// The lowest free surface of the opened cavities [m] (+infinity if none holds water).
  double water_level_m() const;
  /// Liquid volume held in opened cavities [m^3].
  double held_water_volume() const;
  /// Drains cell c if it is exposed, outside the cavities and holds liquid, or if it holds an
  /// opened cavity's liquid above that cavity's level, booking it in `tally`.
  void drain_cell(long c, DrainTally& tally);
  /// Adds cell c's enclosed liquid to `tally`.
  void add_enclosed(long c, EnclosedTally& tally) const;
  /// Liquid volume not open to the outside [m^3].
  double enclosed_liquid_volume() const;
  /// Ice volume fraction of cell c.
  double ice_fraction(long c) const { return m_cells.m[c] * (1 - m_phase.liquid(m_cells.H[c])); }

 private:
  void flood(BlockTeam& team);
  void flood_outside();
  void grow_cavities();
  /// Opens every cavity whose wall is gone somewhere; the first opening's position.
  void open_cavities();
  /// Cell c holds no wall: its ice is below the remnant fraction that draining removes.
  bool ice_free(long c) const;
  /// The height [m] below which water leaks through the face between cavity cell c and its
  /// outside neighbour nb: the face itself if horizontal, c's centre if vertical (the hole's
  /// middle: its bottom is not resolved).
  double opening_height(long c, long nb) const;
  double bottom(long c) const { return m_mesh.centre(c)[1] - 0.5 * m_mesh.dx_m; }
  /// Fraction of cell c's room below `level` (0 above, 1 below).
  double below(long c, double level) const;
  /// Liquid that stays in the body: not exposed, or held in a cavity.
  bool held(long c) const { return !m_exposed[c] || m_cavity[c]; }

  const GridMesh& m_mesh;
  const PhaseRelation& m_phase;
  CellState& m_cells;
  bool m_drain = true;
  bool m_broke_through = false;
  std::optional<std::array<double, 3>> m_opening;  ///< the first opening, until reported
  std::vector<char> m_exposed, open_now, outside_now, m_cavity, cavity_prev;
  /// Per cavity cell: its cavity's free surface [m] once opened, +infinity while sealed.
  std::vector<double> m_level, level_prev;
  std::vector<std::pair<std::array<double, 3>, double>> m_level_drops;
  std::vector<long> queue;  ///< the flood fill's breadth-first queue
};

}  // namespace thaw::sim
