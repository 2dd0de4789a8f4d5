#include "src/pipeline/water_budget.h"

#include <numbers>

#include "base/check.h"

namespace thaw::pipeline {

double shell_surface_volume_m3(const sim::ShellGeometry& g, double r) {
  constexpr double pi = std::numbers::pi;
  const double ball = 4.0 / 3.0 * pi * r * r * r;
  switch (g.geometry) {
    case sim::Geometry::sphere:
      return ball;
    case sim::Geometry::cylinder:
      return pi * r * r * g.length_m + ball;
    case sim::Geometry::planar: {
      const double s = g.lateral_size_m;
      return 2 * s * s * r + 2 * pi * s * r * r + ball;
    }
  }
  return ball;
}

std::vector<WaterBudget> water_budget(const std::vector<sim::InterfaceRecord>& rows,
                                      const sim::ShellGeometry& geometry, double rho_ice,
                                      double rho_water) {
  std::vector<WaterBudget> out;
  if (rows.empty()) return out;
  THAW_CHECK(rho_ice > 0 && rho_water > 0, "densities must be positive");
  const auto volume = [&](double r) { return shell_surface_volume_m3(geometry, r); };
  const double v_outer0 = volume(rows.front().outer_radius_m);
  const double v_core0 = volume(rows.front().inner_radius_m);
  bool had_ice = false, spilled = false;
  for (const auto& row : rows) {
    const bool has_ice = row.outer_radius_m > row.inner_radius_m;
    spilled = spilled || (had_ice && !has_ice);
    had_ice = had_ice || has_ice;
    const double v_outer = volume(row.outer_radius_m), v_core = volume(row.inner_radius_m);
    WaterBudget b;
    b.ice_mass_kg = rho_ice * (v_outer - v_core);
    // The outer surface only recedes (ablation); rounding may leave -1 ulp.
    b.drained_melt_mass_kg = rho_ice * std::max(0.0, v_outer0 - v_outer);
    const double core = rho_water * v_core0 + rho_ice * (v_core - v_core0);
    (spilled ? b.spilled_mass_kg : b.core_water_mass_kg) = core;
    b.puddle_volume_m3 = (b.drained_melt_mass_kg + b.spilled_mass_kg) / rho_water;
    out.push_back(b);
  }
  return out;
}

}  // namespace thaw::pipeline
