#include "sim/grid/conduction_operator.h"

#include <algorithm>

namespace thaw::sim {

ConductionOperator::ConductionOperator(const GridMesh& mesh, const PhaseRelation& phase,
                                       const GridProblem& problem, const CellState& cells,
                                       const std::vector<double>& surface_area)
    : m_mesh(mesh),
      m_phase(phase),
      m_problem(problem),
      m_cells(cells),
      m_surface_area(surface_area),
      m_air_diameter_m(problem.air_diameter_m) {
  for (auto* v : {&kx, &ky, &kz, &bq0, &bq1}) v->assign(static_cast<std::size_t>(mesh.n), 0.0);
}

/// Sub-cell front reconstruction: a cell at the melting point (0 <= H <= L_v) next to a cell
/// in a pure phase P holds the front, at T_m, at depth f_P dx from their shared face, where
/// f_P is its volume fraction of P (the phase on the neighbour's side of a front crossing the
/// cell parallel to the face). The heat between the pure cell's centre and the front flows
/// through phase P only, over dx/2 + f_P dx. (The plain enthalpy method puts T_m at the cell
/// centre whatever f is: an O(1) relative flux error next to the front, which makes the front
/// position first order; see docs/simulate.md for the measured orders.) Otherwise the
/// harmonic mean of the fraction-weighted conductivities over the two half cells.
double ConductionOperator::face_conductance_per_area(long a, long b) const {
  const std::vector<double>& H = m_cells.H;
  const double dx = m_mesh.dx_m;
  const bool melting_a = m_phase.melting(H[a]), melting_b = m_phase.melting(H[b]);
  if (melting_a != melting_b) {
    const long front_cell = melting_a ? a : b, pure_cell = melting_a ? b : a;
    const bool water = H[pure_cell] > m_phase.latent;
    const double f = m_phase.liquid(H[front_cell]);
    return (water ? m_phase.kw : m_phase.ki) / (dx * (0.5 + (water ? f : 1 - f)));
  }
  const double ka = m_phase.conductivity(H[a]), kb = m_phase.conductivity(H[b]);
  return 2 * ka * kb / ((ka + kb) * dx);  // harmonic mean over two half cells
}

void ConductionOperator::assemble(long c, int i, int j, int k) {
  const std::vector<double>& m = m_cells.m;
  const std::vector<double>& H = m_cells.H;
  const GridProblem& p = m_problem;
  const int nx = m_mesh.nx, ny = m_mesh.ny, nz = m_mesh.nz;
  const bool axisymmetric = m_mesh.axisymmetric;
  const double dx = m_mesh.dx_m;
  const long nxy = m_mesh.nxy();
  kx[c] = ky[c] = kz[c] = bq0[c] = bq1[c] = 0;
  if (m[c] == 0) return;
  const double kc = m_phase.conductivity(H[c]);
  auto face = [&](long nb, double area) {
    return m[nb] == 0 ? 0.0 : area * face_conductance_per_area(c, nb);
  };
  if (i + 1 < nx) kx[c] = face(c + 1, m_mesh.area_x[i]);
  if (j + 1 < ny) ky[c] = face(c + nx, m_mesh.area_y[i]);
  if (k + 1 < nz) kz[c] = face(c + nxy, m_mesh.area_z);
  // Held walls: two-point flux over half a cell.
  auto wall = [&](const GridWall& w, double area) {
    if (!w.held || area == 0) return;
    const double g = area * kc / (0.5 * dx);
    bq0[c] += g * w.temperature_c;
    bq1[c] += g;
  };
  if (i == 0) wall(p.walls[0], axisymmetric ? 0.0 : m_mesh.area_x[0]);
  if (i == nx - 1) wall(p.walls[1], m_mesh.area_x[i]);
  if (j == 0) wall(p.walls[2], m_mesh.area_y[i]);
  if (j == ny - 1) wall(p.walls[3], m_mesh.area_y[i]);
  if (!axisymmetric && k == 0) wall(p.walls[4], m_mesh.area_z);
  if (!axisymmetric && k == nz - 1) wall(p.walls[5], m_mesh.area_z);
  const double a = m_surface_area[c];
  if (a > 0) {
    switch (p.surface_kind) {
      case OuterBoundary::convective: {
        // The film coefficient in series with the conduction between the cell's temperature
        // point and the surface, half a cell (as for a held surface below): film (T_air - T_c)
        // alone puts the surface at the cell centre, an O(film dx / k) relative excess of the
        // flux (first order; 1.4 % at film = 100 W/(m^2 K), dx = 0.625 mm). A cell at the
        // melting point holds the front, at T_m, on the surface (ablation) or within it: no
        // added resistance.
        const double film = p.heat_transfer_coefficient_w_m2k;
        const bool at_front = m_phase.melting(H[c]);
        const double g = at_front ? a * film : a / (1 / film + 0.5 * dx / kc);
        bq0[c] += g * p.surface_temperature_c;
        bq1[c] += g;
        break;
      }
      case OuterBoundary::temperature: {
        const double g = a * kc / (0.5 * dx);
        bq0[c] += g * p.surface_temperature_c;
        bq1[c] += g;
        break;
      }
      case OuterBoundary::flux:
        bq0[c] += a * p.flux_w_m2;
        break;
      case OuterBoundary::insulated:
        break;
      case OuterBoundary::air: {
        // The air's flux q(T_s) (sim/boundary/air_model.h; a sphere of the body's volume), frozen
        // over the step as its tangent at the step's surface temperature: a film
        // htc = -dq/dT_s (at least the convective h) towards T_eff = T_s + q / htc, then as the
        // convective kind. The surface is at T_m on a cell holding the front, else taken at the
        // cell's temperature (the film's linearisation point only; the half cell stays in series).
        const bool at_front = m_phase.melting(H[c]);
        const double ts = at_front ? p.materials.melting_point_c : m_cells.T[c];
        const AirBodySize body{AirBody::sphere, m_air_diameter_m};
        const AirFlux f = air_heat_flux(p.air, body, ts);
        const double dt = 1e-4;
        const double slope = (air_heat_flux(p.air, body, ts + dt).total_w_m2() -
                              air_heat_flux(p.air, body, ts - dt).total_w_m2()) /
                             (2 * dt);
        const double film = std::max(-slope, f.heat_transfer_coefficient_w_m2k);
        const double t_eff = ts + f.total_w_m2() / film;
        const double g = at_front ? a * film : a / (1 / film + 0.5 * dx / kc);
        bq0[c] += g * t_eff;
        bq1[c] += g;
        break;
      }
    }
  }
}

}  // namespace thaw::sim
