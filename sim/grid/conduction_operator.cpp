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
      m_air_diameter_m(problem.air_diameter_m),
      m_surface{problem.surface_kind, problem.surface_temperature_c,
                problem.heat_transfer_coefficient_w_m2k, problem.flux_w_m2, problem.air} {
  for (auto* v : {&kx, &ky, &kz, &bq0, &bq1}) v->assign(static_cast<std::size_t>(mesh.n), 0.0);
  if (!problem.face_conditions.empty()) {
    fq0.assign(3 * static_cast<std::size_t>(mesh.n), 0.0);
    fq1.assign(3 * static_cast<std::size_t>(mesh.n), 0.0);
    fface.assign(3 * static_cast<std::size_t>(mesh.n), kNoFace);
  }
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
  if (!fface.empty())
    for (int slot = 0; slot < 3; ++slot) fface[3 * static_cast<std::size_t>(c) + slot] = kNoFace;
  const double a = m_surface_area[c];
  if (!(a > 0)) return;
  if (p.face_conditions.empty()) {
    const auto [q0, q1] = surface_terms(c, m_surface, a, kc);
    bq0[c] += q0;
    bq1[c] += q1;
    return;
  }
  // Faces with conditions of their own: the cell's surface split by its normal, each part's
  // terms kept for the heat by face.
  const FaceWeights w = body_face_weights(p.face_shape, surface_normal(c, i, j, k), axisymmetric,
                                          p.face_of_cell.empty() ? 0 : p.face_of_cell[c]);
  for (std::size_t f = 0; f < p.face_conditions.size(); ++f) {
    if (!(w[f] > 0)) continue;
    const auto [q0, q1] = surface_terms(c, p.face_conditions[f], a * w[f], kc);
    bq0[c] += q0;
    bq1[c] += q1;
    // one slot per axis (box: faces 2a and 2a + 1 never both) or for the ends and the side
    const std::size_t slot = 3 * static_cast<std::size_t>(c) +
                             (p.face_shape == ShapeKind::box ? f / 2 : (f < 2 ? 0 : 1));
    fq0[slot] = q0;
    fq1[slot] = q1;
    fface[slot] = static_cast<std::uint8_t>(f);
  }
}

std::array<double, 3> ConductionOperator::surface_normal(long c, int i, int j, int k) const {
  const std::vector<double>& m = m_cells.m;
  const auto diff = [&](bool has_lo, bool has_hi, long step) {
    return (has_hi ? m[c + step] : m[c]) - (has_lo ? m[c - step] : m[c]);
  };
  return {-diff(i > 0, i + 1 < m_mesh.nx, 1), -diff(j > 0, j + 1 < m_mesh.ny, m_mesh.nx),
          m_mesh.axisymmetric ? 0.0 : -diff(k > 0, k + 1 < m_mesh.nz, m_mesh.nxy())};
}

FaceWeights ConductionOperator::boundary_heat_by_face(long c, int i, int j, int k,
                                                      double tc) const {
  const GridProblem& p = m_problem;
  double rest = boundary_heat(c, tc);
  FaceWeights out{};
  if (!fface.empty())
    for (std::size_t s = 3 * static_cast<std::size_t>(c), end = s + 3; s < end; ++s)
      if (fface[s] != kNoFace) {
        const double q = fq0[s] - fq1[s] * tc;
        out[fface[s]] += q;
        rest -= q;
      }
  // The rest (all of it when the faces share one condition; else a held wall's, or round-off)
  // by the surface's normal.
  if (rest != 0) {
    const FaceWeights w =
        body_face_weights(p.face_shape, surface_normal(c, i, j, k), m_mesh.axisymmetric,
                          p.face_of_cell.empty() ? 0 : p.face_of_cell[c]);
    for (std::size_t f = 0; f < kMaxBodyFaces; ++f) out[f] += w[f] * rest;
  }
  return out;
}

std::array<double, 2> ConductionOperator::surface_terms(long c, const SurfaceCondition& s, double a,
                                                        double kc) const {
  const std::vector<double>& H = m_cells.H;
  const double dx = m_mesh.dx_m;
  switch (s.kind) {
    case OuterBoundary::convective: {
      // The film coefficient in series with the conduction between the cell's temperature
      // point and the surface, half a cell (as for a held surface below): film (T_air - T_c)
      // alone puts the surface at the cell centre, an O(film dx / k) relative excess of the
      // flux (first order; 1.4 % at film = 100 W/(m^2 K), dx = 0.625 mm). A cell at the
      // melting point holds the front, at T_m, on the surface (ablation) or within it: no
      // added resistance.
      const double film = s.heat_transfer_coefficient_w_m2k;
      const bool at_front = m_phase.melting(H[c]);
      const double g = at_front ? a * film : a / (1 / film + 0.5 * dx / kc);
      return {g * s.temperature_c, g};
    }
    case OuterBoundary::temperature: {
      const double g = a * kc / (0.5 * dx);
      return {g * s.temperature_c, g};
    }
    case OuterBoundary::flux:
      return {a * s.flux_w_m2, 0.0};
    case OuterBoundary::insulated:
      return {0.0, 0.0};
    case OuterBoundary::air: {
      // The air's flux q(T_s) (sim/boundary/air_model.h; a sphere of the body's volume), frozen
      // over the step as its tangent at the step's surface temperature: a film
      // htc = -dq/dT_s (at least the convective h) towards T_eff = T_s + q / htc, then as the
      // convective kind. The surface is at T_m on a cell holding the front, else taken at the
      // cell's temperature (the film's linearisation point only; the half cell stays in series).
      const bool at_front = m_phase.melting(H[c]);
      const double ts = at_front ? m_problem.materials.melting_point_c : m_cells.T[c];
      const AirBodySize body{AirBody::sphere, m_air_diameter_m};
      const AirFlux f = air_heat_flux(s.air, body, ts);
      const double dt = 1e-4;
      const double slope = (air_heat_flux(s.air, body, ts + dt).total_w_m2() -
                            air_heat_flux(s.air, body, ts - dt).total_w_m2()) /
                           (2 * dt);
      const double film = std::max(-slope, f.heat_transfer_coefficient_w_m2k);
      const double t_eff = ts + f.total_w_m2() / film;
      const double g = at_front ? a * film : a / (1 / film + 0.5 * dx / kc);
      return {g * t_eff, g};
    }
  }
  return {0.0, 0.0};
}

}  // namespace thaw::sim
