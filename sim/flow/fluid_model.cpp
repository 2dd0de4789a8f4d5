// Water's density and viscosity curves and the Boussinesq buoyancy (fluid_model.h).
#include "sim/flow/fluid_model.h"

#include <algorithm>
#include <cmath>

namespace thaw::sim::flow {

double water_density_kg_m3(double temperature_c) {
  return kWaterDensityMaxKgM3 *
         (1.0 -
          9.2793e-6 * std::pow(std::abs(temperature_c - kWaterDensityMaxTemperatureC), 1.894816));
}

double water_viscosity_pa_s(double temperature_c) {
  // CRC Handbook (97th ed.), viscosity of water at 0.1 MPa, every 5 C from 0 C [mPa s].
  static constexpr double kMilliPaS[] = {1.793, 1.519, 1.307, 1.138, 1.002,
                                         0.890, 0.797, 0.719, 0.653};
  constexpr int kLast = static_cast<int>(sizeof(kMilliPaS) / sizeof(kMilliPaS[0])) - 1;
  const double s = std::clamp(temperature_c / 5.0, 0.0, static_cast<double>(kLast));
  const int i = std::min(static_cast<int>(s), kLast - 1);
  const double f = s - i;
  return 1e-3 * (kMilliPaS[i] * (1.0 - f) + kMilliPaS[i + 1] * f);
}

double FluidModel::buoyancy_m_s2(double temperature_c) const {
  if (density == Density::linear)
    return gravity_m_s2 * expansion_per_k * (temperature_c - reference_temperature_c);
  return -gravity_m_s2 * (water_density_kg_m3(temperature_c) - kWaterDensityMaxKgM3) /
         reference_density_kg_m3;
}

double FluidModel::kinematic_viscosity_m2_s(double temperature_c) const {
  const double mu = viscosity_pa_s > 0 ? viscosity_pa_s : water_viscosity_pa_s(temperature_c);
  return mu / reference_density_kg_m3;
}

}  // namespace thaw::sim::flow
