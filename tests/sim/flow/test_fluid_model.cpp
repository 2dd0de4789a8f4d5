// Water's density and viscosity curves (sim/flow/fluid_model.h) against the values their sources
// print, and the Boussinesq buoyancy of the two density models.
#include "sim/flow/fluid_model.h"

#include <gtest/gtest.h>

namespace thaw::sim::flow {
namespace {

TEST(FluidModel, WaterDensityMatchesThePublishedValues) {
  // /work/shared/reference facts: rho(0) = 999.842, rho(4.03) = 999.972, rho(10) = 999.698,
  // rho(20) = 998.204 kg/m^3, printed to 3 decimals: +-0.0005 plus the fit's rounding.
  EXPECT_NEAR(water_density_kg_m3(0.0), 999.842, 1e-3);
  EXPECT_NEAR(water_density_kg_m3(4.0293), 999.972, 1e-9);
  EXPECT_NEAR(water_density_kg_m3(10.0), 999.698, 1e-3);
  EXPECT_NEAR(water_density_kg_m3(20.0), 998.204, 1e-3);
  // The maximum: lighter on both sides, so buoyancy turns over at 4.0293 C.
  EXPECT_LT(water_density_kg_m3(4.0), water_density_kg_m3(4.0293));
  EXPECT_LT(water_density_kg_m3(4.06), water_density_kg_m3(4.0293));
}

TEST(FluidModel, WaterViscosityInterpolatesTheTable) {
  EXPECT_DOUBLE_EQ(water_viscosity_pa_s(0.0), 1.793e-3);
  EXPECT_DOUBLE_EQ(water_viscosity_pa_s(20.0), 1.002e-3);
  EXPECT_NEAR(water_viscosity_pa_s(2.5), 0.5 * (1.793e-3 + 1.519e-3), 1e-15);
  EXPECT_DOUBLE_EQ(water_viscosity_pa_s(-3.0), 1.793e-3);  // held at the table's ends
  EXPECT_DOUBLE_EQ(water_viscosity_pa_s(90.0), 0.653e-3);
}

TEST(FluidModel, BuoyancyOfBothDensityModels) {
  FluidModel water;
  // Water at 0 C and at 8 C is lighter than at 4.03 C: both rise against 4 C water.
  EXPECT_GT(water.buoyancy_m_s2(0.0), water.buoyancy_m_s2(4.0293));
  EXPECT_GT(water.buoyancy_m_s2(8.0), water.buoyancy_m_s2(4.0293));
  EXPECT_NEAR(water.buoyancy_m_s2(10.0) - water.buoyancy_m_s2(4.0293),
              9.81 * (999.972 - water_density_kg_m3(10.0)) / 999.972, 1e-15);
  FluidModel linear;
  linear.density = FluidModel::Density::linear;
  linear.reference_density_kg_m3 = 1000;
  linear.expansion_per_k = 2e-4;
  linear.reference_temperature_c = 10;
  linear.viscosity_pa_s = 1e-3;
  EXPECT_DOUBLE_EQ(linear.buoyancy_m_s2(15.0), 9.81 * 2e-4 * 5.0);
  EXPECT_DOUBLE_EQ(linear.kinematic_viscosity_m2_s(3.0), 1e-6);
}

}  // namespace
}  // namespace thaw::sim::flow
