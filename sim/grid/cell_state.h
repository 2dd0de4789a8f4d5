#pragma once
// The grid solver's per-cell state, shared by its parts (conduction operator, Newton solve,
// surface areas, cavities and drain, time stepper): the material fraction and its enthalpy,
// and the step's working copies. Each part reads what it needs and writes only what its own
// header says it writes. Knows nothing of the physics beyond the names.
#include <vector>

namespace thaw::sim {

struct CellState {
  /// Sizes every array to n cells (zeros).
  void resize(long n) {
    for (auto* v : {&m, &H, &H_start, &T, &T_start, &f_start, &rate})
      v->assign(static_cast<std::size_t>(n), 0.0);
  }
  std::vector<double> m;        ///< volume fraction of material (ice + water) in the cell [0, 1]
  std::vector<double> H;        ///< enthalpy per unit volume of material [J/m^3] (phase_relation.h)
  std::vector<double> H_start;  ///< H at the start of the step being taken
  std::vector<double> T;        ///< temperature [C] of Newton's current iterate (0 in air)
  std::vector<double> T_start, f_start;  ///< temperature and liquid fraction at the step's start
  std::vector<double> rate;  ///< each cell's rate of temperature change in the last step [K/s]
};

}  // namespace thaw::sim
