// The differentially heated square cavity (de Vahl Davis 1983; Pr 0.71) with the MAC solver
// (sim/flow/flow_solver.h), marched from rest to steady state: the hot wall's mean Nusselt
// number against the high-accuracy reference of Hortmann, Peric & Scheuerer (1990, Int. J.
// Numer. Methods Fluids 11:189; 640 x 640 cells, extrapolated) and against de Vahl Davis's
// benchmark values, with Richardson extrapolation and the observed order of convergence.
// Unit: Ra 1e4 on 16^2 and 32^2. e2e (test_cavity_e2e.cpp): the third grid and Ra 1e5.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/sim/flow/cavity.h"
#include "tests/sim/flow/cavity_reference.h"

namespace thaw::sim::flow {
namespace {

TEST(Cavity, Rayleigh1e4ConvergesAtSecondOrderToTheReference) {
  double nu[2];
  const int cells[2] = {16, 32};
  for (int g = 0; g < 2; ++g) {
    FlowSolver s(test::cavity_problem(1e4, 0.71, cells[g]));
    const test::CavityResult r = test::run_cavity_to_steady(s, 1e-6, 1e-5, 200);
    std::printf("Ra 1e4, %d^2: Nu hot %.5f cold %.5f at t = %.1f after %ld steps\n", cells[g],
                r.nusselt_hot, r.nusselt_cold, r.time, r.steps);
    // Steady: the heat in at the hot wall leaves at the cold wall.
    EXPECT_NEAR(r.nusselt_hot, r.nusselt_cold, 1e-5 * r.nusselt_hot);
    nu[g] = r.nusselt_hot;
  }
  const test::CavityCheck c = test::check_two_grids(nu[0], nu[1], test::kHortmannNu1e4);
  std::printf("Richardson %.5f (reference %.5f, error %.3f %%), observed order %.2f\n",
              c.extrapolated, test::kHortmannNu1e4, 100 * c.extrapolated_error, c.order);
  // Second-order scheme: the order from the errors against the reference is 2 up to the next
  // term of the expansion (h/L = 1/16 on the coarse grid): 2 +- 0.3.
  EXPECT_NEAR(c.order, 2.0, 0.3);
  // The extrapolated value removes the h^2 term; what is left is at most a tenth of the fine
  // grid's error estimate (N16 - N32)/3.
  EXPECT_LT(std::abs(c.extrapolated - test::kHortmannNu1e4), 0.1 * std::abs(nu[0] - nu[1]) / 3);
  // de Vahl Davis (1983) 2.243, the figure the issue names: within 1 %.
  EXPECT_NEAR(c.extrapolated, test::kDeVahlDavisNu1e4, 0.01 * test::kDeVahlDavisNu1e4);
}

}  // namespace
}  // namespace thaw::sim::flow
