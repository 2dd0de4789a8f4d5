#pragma once
// The differentially heated square cavity (de Vahl Davis 1983) in free-fall units, shared by the
// flow tests: side L = 1 m, g beta (T_h - T_c) = 1 m/s^2, walls x_min at +1/2, x_max at -1/2,
// top and bottom adiabatic; nu = sqrt(Pr / Ra), alpha = 1 / sqrt(Ra Pr).
#include <cmath>
#include <cstdio>

#include "sim/flow/flow_solver.h"

namespace thaw::sim::flow::test {

inline FlowProblem cavity_problem(double rayleigh, double prandtl, int cells) {
  FlowProblem p;
  p.grid.geometry = FlowGeometry::planar;
  p.grid.n = {cells, cells, 1};
  p.grid.h_m = 1.0 / cells;
  p.fluid.density = FluidModel::Density::linear;
  p.fluid.reference_density_kg_m3 = 1.0;
  p.fluid.expansion_per_k = 1.0;
  p.fluid.reference_temperature_c = 0.0;
  p.fluid.gravity_m_s2 = 1.0;
  p.fluid.viscosity_pa_s = std::sqrt(prandtl / rayleigh);  // rho_0 = 1: nu
  p.thermal_diffusivity_m2_s = 1.0 / std::sqrt(rayleigh * prandtl);
  p.walls[x_min] = {WallCondition::Kind::temperature, 0.5};
  p.walls[x_max] = {WallCondition::Kind::temperature, -0.5};
  return p;
}

struct CavityResult {
  double nusselt_hot = 0, nusselt_cold = 0, time = 0;
  long steps = 0;
  int last_pressure_iterations = 0;
};

/// Marches the cavity from rest at T = 0 until the largest temperature change rate is below
/// `rate_tolerance` (free-fall units) and the two walls' Nusselt numbers agree to
/// `balance_tolerance`, or until max_time.
inline CavityResult run_cavity_to_steady(FlowSolver& s, double rate_tolerance,
                                         double balance_tolerance, double max_time) {
  const double alpha = s.problem().thermal_diffusivity_m2_s;
  CavityResult r;
  std::vector<double> before;
  for (;;) {
    const double dt = s.stable_time_step_s();
    before = s.temperature_c();
    const FlowStepReport rep = s.step(dt);
    ++r.steps;
    r.last_pressure_iterations = rep.pressure_iterations;
    double rate = 0;
    for (std::size_t c = 0; c < before.size(); ++c)
      rate = std::max(rate, std::abs(s.temperature_c()[c] - before[c]) / dt);
    r.nusselt_hot = s.wall_heat_flow_k_m3_s(x_min) / alpha;
    r.nusselt_cold = -s.wall_heat_flow_k_m3_s(x_max) / alpha;
    r.time = s.time_s();
    if (rate < rate_tolerance &&
        std::abs(r.nusselt_hot - r.nusselt_cold) < balance_tolerance * r.nusselt_hot)
      break;
    if (r.time > max_time) break;
  }
  return r;
}

}  // namespace thaw::sim::flow::test
