// The differentially heated cavity on finer grids (e2e: about a minute of CPU): Ra 1e4 on 16^2,
// 32^2, 64^2 with the observed order from the three grids alone; Ra 1e5 on 32^2 and 64^2,
// Richardson-extrapolated against Hortmann, Peric & Scheuerer (1990). See test_cavity.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/sim/flow/cavity.h"
#include "tests/sim/flow/cavity_reference.h"

namespace thaw::sim::flow {
namespace {

double steady_nusselt(double rayleigh, int cells) {
  FlowSolver s(test::cavity_problem(rayleigh, 0.71, cells));
  const test::CavityResult r = test::run_cavity_to_steady(s, 1e-6, 1e-5, 400);
  std::printf(
      "Ra %.0e, %d^2: Nu hot %.5f cold %.5f at t = %.1f after %ld steps, max |div u| "
      "%.2e\n",
      rayleigh, cells, r.nusselt_hot, r.nusselt_cold, r.time, r.steps, s.max_divergence_per_s());
  EXPECT_NEAR(r.nusselt_hot, r.nusselt_cold, 1e-5 * r.nusselt_hot);
  return r.nusselt_hot;
}

TEST(CavityE2e, Rayleigh1e4ObservedOrderFromThreeGrids) {
  const double n16 = steady_nusselt(1e4, 16), n32 = steady_nusselt(1e4, 32),
               n64 = steady_nusselt(1e4, 64);
  const double p = test::observed_order(n16, n32, n64);
  const double extrapolated = n64 + (n64 - n32) / (std::pow(2.0, p) - 1.0);
  std::printf("Ra 1e4: observed order %.3f, extrapolated %.5f (reference %.5f, %.3f %%)\n", p,
              extrapolated, test::kHortmannNu1e4,
              100 * (extrapolated - test::kHortmannNu1e4) / test::kHortmannNu1e4);
  EXPECT_NEAR(p, 2.0, 0.2);  // the scheme's formal order; h/L <= 1/16
  EXPECT_NEAR(extrapolated, test::kHortmannNu1e4, 0.1 * std::abs(n32 - n64) / 3);
}

TEST(CavityE2e, Rayleigh1e5WithinATenthOfAPercentAfterExtrapolation) {
  const double n32 = steady_nusselt(1e5, 32), n64 = steady_nusselt(1e5, 64);
  const test::CavityCheck c = test::check_two_grids(n32, n64, test::kHortmannNu1e5);
  std::printf("Ra 1e5: Richardson %.5f (reference %.5f, %.3f %%), order vs reference %.2f\n",
              c.extrapolated, test::kHortmannNu1e5, 100 * c.extrapolated_error, c.order);
  EXPECT_NEAR(c.order, 2.0, 0.3);
  EXPECT_NEAR(c.extrapolated, test::kHortmannNu1e5, 0.1 * std::abs(n32 - n64) / 3);
  EXPECT_NEAR(c.extrapolated, test::kDeVahlDavisNu1e5, 0.01 * test::kDeVahlDavisNu1e5);
}

}  // namespace
}  // namespace thaw::sim::flow
