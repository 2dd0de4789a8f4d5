// The grid enthalpy solver against the planar Neumann problem, the full set (end-to-end, a few
// seconds: label e2e): melting and freezing, one and two phases, Stefan numbers 0.006 to 2.05,
// the real ice | water properties and a set with the conductivity contrast reversed, in the
// axisymmetric and the 3D grid. The two-phase problems need the far phase's thermal layer in the
// grid (six thermal lengths: 10-25 front lengths), hence the longer runs. Same assertions and
// derivation as the unit subset (test_enthalpy_solver.cpp, "other Stefan numbers").
#include <gtest/gtest.h>

#include "tests/sim/grid/planar_neumann_grid.h"

namespace thaw::sim {
namespace {

std::vector<test::PlanarNeumann> all_cases() {
  const Materials d = default_materials();
  const Materials r = test::reversed_materials();
  return {
      // the case: freezing from -20 C into water at +5 C (St_ice 0.12, St_water 0.07)
      {"freeze -20|+5", d, false, -20, 5},
      {"freeze -1|0 (St 0.006)", d, false, -1, 0},
      // large Stefan number freezing: -100 C into water at +2 C (St_ice 0.61)
      {"freeze -100|+2 (St 0.61)", d, false, -100, 2},
      {"melt +10|0 (St 0.14)", d, true, 10, 0},
      // two phases melting: +30 C into ice at -5 C (St_water 0.41, St_ice 0.03)
      {"melt +30|-5", d, true, 30, -5},
      {"melt +150|0 (St 2.05)", d, true, 150, 0},
      // reversed conductivity contrast, two phases each way
      {"reversed melt +20|-10", r, true, 20, -10},
      {"reversed freeze -20|+10", r, false, -20, 10},
  };
}

void expect_all(GridField::Geometry g) {
  using S = test::NeumannStudy;
  for (const test::PlanarNeumann& pn : all_cases()) {
    const S st = test::study_planar_neumann(pn, g);
    EXPECT_LT(st.exact_identity, 1e-6) << pn.name;
    EXPECT_GE(S::order(st.front), 1.5) << pn.name;
    EXPECT_GE(S::pair_order(st.front, 0), 1.0) << pn.name;
    EXPECT_GE(S::pair_order(st.front, 1), 1.0) << pn.name;
    EXPECT_GE(S::order(st.heat), 1.5) << pn.name;
    EXPECT_GE(S::pair_order(st.heat, 0), 1.0) << pn.name;
    EXPECT_GE(S::pair_order(st.heat, 1), 1.0) << pn.name;
    EXPECT_LT(st.heat_vs_enthalpy, 1e-12) << pn.name;
    EXPECT_LT(st.step_energy, 1e-8) << pn.name;
  }
}

TEST(EnthalpySolverE2e, NeumannAllCasesAxisymmetric) {
  expect_all(GridField::Geometry::axisymmetric);
}
TEST(EnthalpySolverE2e, NeumannAllCases3d) {
  expect_all(GridField::Geometry::cartesian3d);
}

}  // namespace
}  // namespace thaw::sim
