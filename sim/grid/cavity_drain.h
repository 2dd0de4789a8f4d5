#pragma once
// Cavities and drainage of the grid solver: which cells are open to the outside air (a flood
// fill from the grid's air border through cells less than half ice), which are exposed
// (outside or next to it), the melt that drains from exposed cells (its enthalpy booked as
// drained; ice remnants below kRemnantFraction go with it), the liquid still enclosed, and the
// moment an enclosed cavity joins the outside (break-through). Writes m and H of drained cells
// and its own openness arrays. Knows nothing of heat conduction, Newton or step sizes.
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

  /// exposed[c]: cell c is outside, or next to a cell outside.
  const std::vector<char>& exposed() const { return m_exposed; }
  /// Openness from the current state, and remembered as the previous step's (the constructor's
  /// start: the initial state drains nothing by definition).
  void classify(BlockTeam& team);
  /// open_now[c] from the cell's ice fraction (less than half ice).
  void mark_open(long c) { open_now[c] = ice_fraction(c) < 0.5; }
  /// outside_now from open_now: a breadth-first flood from the grid's border (serial).
  void fill_outside();
  /// exposed[c] from outside_now.
  void exposure(long c, int i, int j, int k);
  /// Keeps cell c's openness as the previous step's.
  void remember_openness(long c);
  /// After fill_outside: a former cavity cell now outside means break-through, at the first
  /// wall cell that opened this step next to the former cavity. Returns that cell, or -1 (no
  /// break-through now, or one already reported). Serial.
  long detect_break_through();
  bool broke_through() const { return m_broke_through; }
  /// Drains cell c if it is exposed and holds liquid, booking it in `tally`.
  void drain_cell(long c, DrainTally& tally);
  /// Adds cell c's enclosed liquid to `tally`.
  void add_enclosed(long c, EnclosedTally& tally) const;
  /// Liquid volume not open to the outside [m^3].
  double enclosed_liquid_volume() const;
  /// Ice volume fraction of cell c.
  double ice_fraction(long c) const { return m_cells.m[c] * (1 - m_phase.liquid(m_cells.H[c])); }

 private:
  void flood(BlockTeam& team);

  const GridMesh& m_mesh;
  const PhaseRelation& m_phase;
  CellState& m_cells;
  bool m_drain = true;
  bool m_broke_through = false;
  std::vector<char> open_prev, enclosed_prev, m_exposed, open_now, outside_now;
  std::vector<long> queue;  ///< the flood fill's breadth-first queue
};

}  // namespace thaw::sim
