#include "sim/grid/grid_flow.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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
/// Cells of ice or air kept around the liquid when the box moves (it moves again only when the
/// liquid reaches the box's outermost cells).
constexpr int kBoxMargin = 2;
/// The solves' tolerances in the coupled flow: the projection leaves a net outflow of 1e-7 of the
/// largest face flow per cell (a sensible-heat source of that order against the advected heat;
/// the advected rates sum to zero whatever it is), the viscous increment 1e-6 of its size.
constexpr double kPressureTolerance = 1e-7;
constexpr double kImplicitTolerance = 1e-6;

flow::FlowProblem flow_problem(const GridMesh& mesh, const GridProblem& p,
                               const std::array<int, 3>& cells) {
  flow::FlowProblem f;
  f.grid.geometry =
      mesh.axisymmetric ? flow::FlowGeometry::axisymmetric : flow::FlowGeometry::cartesian3d;
  f.grid.n = cells;
  f.grid.h_m = mesh.dx_m;
  f.fluid = p.fluid;
  f.thermal_diffusivity_m2_s =
      p.materials.water_conductivity_w_mk / p.materials.water_heat_capacity();
  f.pressure_tolerance = kPressureTolerance;
  f.implicit_tolerance = kImplicitTolerance;
  return f;  // walls adiabatic and no-slip: the box's border is ice or air, held by the drag
}

}  // namespace

GridFlow::GridFlow(const GridMesh& mesh, const PhaseRelation& phase, const GridProblem& problem,
                   const CellState& cells, const std::vector<char>& exposed)
    : m_mesh(mesh), m_phase(phase), m_problem(problem), m_cells(cells), m_exposed(exposed) {
  THAW_CHECK(mesh.axisymmetric || mesh.nz >= 2, "flow: a 3D grid needs 2 cells along z");
  m_advected_w.assign(static_cast<std::size_t>(mesh.n), 0.0);
}

bool GridFlow::fit_box() {
  const std::vector<double>& m = m_cells.m;
  const std::vector<double>& H = m_cells.H;
  const int dims = m_mesh.axisymmetric ? 2 : 3;
  const std::array<int, 3> cells{m_mesh.nx, m_mesh.ny, m_mesh.axisymmetric ? 1 : m_mesh.nz};
  std::array<int, 3> lo = cells, hi{-1, -1, -1};  // the liquid's cells, inclusive
  for (long c = 0; c < m_mesh.n; ++c) {
    // mostly liquid and not draining: the water (a melting cell next to it is in the margin)
    if (m[c] * m_phase.liquid(H[c]) < 0.5 || m_exposed[c]) continue;
    const long row = c / m_mesh.nx;
    const std::array<int, 3> a{static_cast<int>(c % m_mesh.nx), static_cast<int>(row % m_mesh.ny),
                               static_cast<int>(row / m_mesh.ny)};
    for (int d = 0; d < dims; ++d) {
      lo[d] = std::min(lo[d], a[d]);
      hi[d] = std::max(hi[d], a[d]);
    }
  }
  if (hi[0] < 0) {
    m_flow.reset();
    m_n = {0, 0, 0};
    return false;
  }
  // The box must hold the liquid and one cell more on each side (within the grid).
  bool fits = m_flow != nullptr;
  for (int d = 0; d < dims && fits; ++d) {
    const int need_lo = std::max(0, lo[d] - 1), need_hi = std::min(cells[d] - 1, hi[d] + 1);
    fits = m_lo[d] <= need_lo && need_hi <= m_lo[d] + m_n[d] - 1;
  }
  if (fits) return true;
  std::array<int, 3> new_lo{0, 0, 0}, new_n{1, 1, 1};
  for (int d = 0; d < dims; ++d) {
    new_lo[d] = std::max(0, lo[d] - kBoxMargin);
    if (d == 0 && m_mesh.axisymmetric) new_lo[d] = 0;  // the radius weights start at the axis
    const int last = std::min(cells[d] - 1, hi[d] + kBoxMargin);
    new_n[d] = last - new_lo[d] + 1;
    if (new_n[d] < 2) {  // the flow needs 2 cells per axis
      if (new_lo[d] + 2 <= cells[d])
        new_n[d] = 2;
      else
        new_lo[d] = cells[d] - 2, new_n[d] = 2;
    }
  }
  auto next = std::make_unique<flow::FlowSolver>(flow_problem(m_mesh, m_problem, new_n));
  next->hold_temperature(true);
  if (m_flow) {  // carry the velocities over; faces new to the box start at rest
    const flow::MacGrid& og = m_flow->grid();
    const flow::MacGrid& ng = next->grid();
    for (int d = 0; d < dims; ++d) {
      const std::vector<double>& old_u = m_flow->velocity_m_s(d);
      std::vector<double> u(ng.face_count(d), 0.0);
      const auto nf = ng.face_dims(d), of = og.face_dims(d);
      for (int k = 0; k < nf[2]; ++k)
        for (int j = 0; j < nf[1]; ++j)
          for (int i = 0; i < nf[0]; ++i) {
            const int a[3] = {i + new_lo[0] - m_lo[0], j + new_lo[1] - m_lo[1],
                              k + new_lo[2] - m_lo[2]};
            bool inside = true;
            for (int e = 0; e < 3; ++e) inside = inside && a[e] >= 0 && a[e] < of[e];
            if (inside) u[ng.face(d, i, j, k)] = old_u[og.face(d, a[0], a[1], a[2])];
          }
      // faces on the new box's walls are walls
      for (int k = 0; k < nf[2]; ++k)
        for (int j = 0; j < nf[1]; ++j)
          for (int i = 0; i < nf[0]; ++i) {
            const int along = d == 0 ? i : (d == 1 ? j : k);
            if (along == 0 || along == new_n[d]) u[ng.face(d, i, j, k)] = 0;
          }
      next->set_velocity_m_s(d, std::move(u));
    }
  }
  m_flow = std::move(next);
  m_lo = new_lo;
  m_n = new_n;
  const std::size_t n = m_flow->grid().cell_count();
  m_drag.assign(n, 0.0);
  m_sensible.assign(n, 0.0);
  m_carries.assign(n, 0);
  return true;
}

double GridFlow::cell_velocity_m_s(int d, int i, int j, int k) const {
  if (!m_flow) return 0;
  const int a[3] = {i - m_lo[0], j - m_lo[1], k - m_lo[2]};
  for (int e = 0; e < 3; ++e)
    if (a[e] < 0 || a[e] >= m_n[e]) return 0;
  return m_flow->cell_velocity_m_s(d, a[0], a[1], a[2]);
}

GridFlow::~GridFlow() = default;

double GridFlow::max_step_s() const {
  if (!m_flow) return std::numeric_limits<double>::infinity();
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
  std::fill(m_advected_w.begin(), m_advected_w.end(), 0.0);
  if (!fit_box()) return;
  std::vector<double>& t = m_flow->temperature_c();
  const double cw = m_phase.cw, tm = m_phase.tm;
  const flow::MacGrid& g = m_flow->grid();
  auto grid_cell = [&](int i, int j, int k) {
    return (i + m_lo[0]) + static_cast<long>(m_mesh.nx) *
                               ((j + m_lo[1]) + static_cast<long>(m_mesh.ny) * (k + m_lo[2]));
  };
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const long c = grid_cell(i, j, k);
        const std::size_t b = g.cell(i, j, k);
        const double temperature = m[c] > 0 ? m_phase.temperature(H[c]) : tm;
        t[b] = temperature;
        const double phi = m[c] * m_phase.liquid(H[c]);
        m_drag[b] =
            kCarmanKozenyPerS * (1 - phi) * (1 - phi) / (phi * phi * phi + kCarmanKozenyEpsilon);
        m_carries[b] = m[c] > 0;
        m_sensible[b] = m[c] > 0 ? cw * (temperature - tm) : 0.0;
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
    m_flow_cell_steps += static_cast<double>(g.cell_count());
    left = pieces <= 1 ? 0 : left - h;
  }
  // Advected heat [W]: the flow's per-radian (axisymmetric) transport times the revolution. The
  // box's border cells carry nothing out of the box (no liquid moves there).
  m_flow->advective_transport(m_sensible, m_carries, m_advected_box);
  const double revolution = m_mesh.axisymmetric ? 2 * std::numbers::pi : 1.0;
  for (int k = 0; k < g.n[2]; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i)
        m_advected_w[grid_cell(i, j, k)] = revolution * m_advected_box[g.cell(i, j, k)];
}
}  // namespace thaw::sim
