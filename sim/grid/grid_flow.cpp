#include "sim/grid/grid_flow.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "base/check.h"

namespace thaw::sim {
namespace {

/// Carman-Kozeny constant over rho_0 [1/s] and its regulariser (Brent, Voller & Reid 1988).
constexpr double kCarmanKozenyPerS = 1.6e6 / 1000.0;
constexpr double kCarmanKozenyEpsilon = 1e-3;
/// Courant number of the explicit advection in an enthalpy step.
constexpr double kAdvectionCourant = 0.5;

flow::FlowProblem flow_problem(const GridMesh& mesh, const GridProblem& p) {
  flow::FlowProblem f;
  f.grid.geometry =
      mesh.axisymmetric ? flow::FlowGeometry::axisymmetric : flow::FlowGeometry::cartesian3d;
  f.grid.n = {mesh.nx, mesh.ny, mesh.axisymmetric ? 1 : mesh.nz};
  f.grid.h_m = mesh.dx_m;
  f.fluid = p.fluid;
  f.thermal_diffusivity_m2_s =
      p.materials.water_conductivity_w_mk / p.materials.water_heat_capacity();
  return f;  // walls adiabatic and no-slip: the grid's border is air, held still by the drag
}

}  // namespace

GridFlow::GridFlow(const GridMesh& mesh, const PhaseRelation& phase, const GridProblem& problem,
                   const CellState& cells)
    : m_mesh(mesh), m_phase(phase), m_problem(problem), m_cells(cells) {
  THAW_CHECK(mesh.axisymmetric || mesh.nz >= 2, "flow: a 3D grid needs 2 cells along z");
  m_flow = std::make_unique<flow::FlowSolver>(flow_problem(mesh, problem));
  m_flow->hold_temperature(true);
  const std::size_t n = static_cast<std::size_t>(mesh.n);
  m_advected_w.assign(n, 0.0);
  m_drag.assign(n, 0.0);
  m_sensible.assign(n, 0.0);
  m_carries.assign(n, 0);
}

GridFlow::~GridFlow() = default;

double GridFlow::max_step_s() const {
  const flow::MacGrid& g = m_flow->grid();
  double rate = 0;
  for (int d = 0; d < g.dims(); ++d)
    for (double u : m_flow->velocity_m_s(d)) rate = std::max(rate, std::abs(u));
  return rate > 0 ? kAdvectionCourant * g.h_m / (g.dims() * rate)
                  : std::numeric_limits<double>::infinity();
}

double GridFlow::rayleigh() const {
  const std::vector<double>& m = m_cells.m;
  const std::vector<double>& H = m_cells.H;
  const flow::FluidModel& fluid = m_problem.fluid;
  double volume = 0, t_sum = 0, t_max = m_phase.tm;
  for (long c = 0; c < m_mesh.n; ++c) {
    if (m[c] <= 0) continue;
    const double t = m_phase.temperature(H[c]), f = m_phase.liquid(H[c]);
    volume += m[c] * f * m_mesh.vol[c];
    t_sum += m[c] * f * m_mesh.vol[c] * t;
    if (f >= 0.5) t_max = std::max(t_max, t);
  }
  if (volume <= 0) return 0;
  // The buoyancy's spread over [T_m, warmest liquid] (the ice holds T_m): sampled, with the
  // density maximum itself when it lies inside.
  double b_lo = fluid.buoyancy_m_s2(m_phase.tm), b_hi = b_lo;
  auto take = [&](double t) {
    const double b = fluid.buoyancy_m_s2(t);
    b_lo = std::min(b_lo, b);
    b_hi = std::max(b_hi, b);
  };
  for (int s = 1; s <= 64; ++s) take(m_phase.tm + (t_max - m_phase.tm) * s / 64.0);
  if (flow::kWaterDensityMaxTemperatureC > m_phase.tm && flow::kWaterDensityMaxTemperatureC < t_max)
    take(flow::kWaterDensityMaxTemperatureC);
  const double diameter = std::cbrt(6 * volume / std::numbers::pi);
  const double nu = fluid.kinematic_viscosity_m2_s(t_sum / volume);
  const double alpha = m_problem.materials.water_conductivity_w_mk / m_phase.cw;
  return (b_hi - b_lo) * diameter * diameter * diameter / (nu * alpha);
}

void GridFlow::advance(double dt) {
  const std::vector<double>& m = m_cells.m;
  const std::vector<double>& H = m_cells.H;
  std::vector<double>& t = m_flow->temperature_c();
  const double cw = m_phase.cw, tm = m_phase.tm;
  for (long c = 0; c < m_mesh.n; ++c) {
    const double temperature = m[c] > 0 ? m_phase.temperature(H[c]) : tm;
    t[c] = temperature;
    const double phi = m[c] * m_phase.liquid(H[c]);
    m_drag[c] =
        kCarmanKozenyPerS * (1 - phi) * (1 - phi) / (phi * phi * phi + kCarmanKozenyEpsilon);
    m_carries[c] = m[c] > 0;
    m_sensible[c] = m[c] > 0 ? cw * (temperature - tm) : 0.0;
  }
  m_flow->set_drag_per_s(m_drag);
  // Sub-steps of equal size, each within the flow's stable step.
  double left = dt;
  while (left > 0) {
    const double stable = m_flow->stable_time_step_s();
    const int pieces = static_cast<int>(std::ceil(left / stable - 1e-12));
    const double h = left / std::max(1, pieces);
    m_flow->step(h);
    ++m_flow_steps;
    left = pieces <= 1 ? 0 : left - h;
  }
  // Advected heat [W]: the flow's per-radian (axisymmetric) transport times the revolution.
  m_flow->advective_transport(m_sensible, m_carries, m_advected_w);
  const double revolution = m_mesh.axisymmetric ? 2 * std::numbers::pi : 1.0;
  for (double& q : m_advected_w) q *= revolution;
}

}  // namespace thaw::sim
