#pragma once
// The discrete conduction operator of the grid enthalpy solver: each material cell's face
// conductances to its +x, +y, +z neighbours [W/K] (with the sub-cell front reconstruction) and
// its boundary terms (held walls, the material | air surface: convective, held, flux or
// insulated), frozen over one step at the step's initial state; the net heat rate into a cell
// at given temperatures. The 7-point stencil is matrix-free: neighbour_sum_of applies it.
// Reads the cell state (m, H, T) and the surface areas; writes only its own coefficients.
// Knows nothing of time stepping, Newton or draining.
#include <array>
#include <cstdint>
#include <vector>

#include "sim/grid/body_faces.h"

#include "sim/grid/cell_state.h"
#include "sim/grid/grid_mesh.h"
#include "sim/grid/grid_problem.h"
#include "sim/grid/phase_relation.h"

namespace thaw::sim {

class ConductionOperator {
 public:
  ConductionOperator(const GridMesh& mesh, const PhaseRelation& phase, const GridProblem& problem,
                     const CellState& cells, const std::vector<double>& surface_area);

  /// Cell c's (at i, j, k) conductances and boundary terms at the current m, H and surface
  /// areas. Reads the neighbours' H.
  void assemble(long c, int i, int j, int k);

  /// Net heat rate into cell c (at i, j, k) at the temperatures T of the cell state [W].
  double heat_rate(long c, int i, int j, int k) const {
    const std::vector<double>& T = m_cells.T;
    const double tc = T[c];
    double q0 = bq0[c] - bq1[c] * tc;
    if (m_advected) q0 += (*m_advected)[c];
    return neighbour_sum_of(
        c, i, j, k, [&](long nb) { return T[nb] - tc; }, q0);
  }
  /// The diameter the air's correlations see (kind = air) from the next assembly on [m].
  void set_air_diameter(double diameter_m) { m_air_diameter_m = diameter_m; }

  /// Adds a fixed heat rate per cell [W] to heat_rate (the water's advected heat,
  /// grid_flow.h); nullptr: none. The vector must outlive the operator's use.
  void set_advection(const std::vector<double>* advected_w) { m_advected = advected_w; }
  /// Boundary heat into cell c at temperature tc [W].
  double boundary_heat(long c, double tc) const { return bq0[c] - bq1[c] * tc; }
  /// Sum of cell c's conductances, to its neighbours and its boundaries [W/K].
  double conductance_sum(long c, int i, int j, int k) const {
    const long nxy = m_mesh.nxy();
    const int nx = m_mesh.nx, ny = m_mesh.ny, nz = m_mesh.nz;
    double g = bq1[c];
    if (i + 1 < nx) g += kx[c];
    if (i > 0) g += kx[c - 1];
    if (j + 1 < ny) g += ky[c];
    if (j > 0) g += ky[c - nx];
    if (k + 1 < nz) g += kz[c];
    if (k > 0) g += kz[c - nxy];
    return g;
  }
  /// q0 + the sum over neighbours of K * v(nb), v a function of the neighbour's index; cell c
  /// is at (i, j, k). The terms are added in a fixed order (+x, -x, +y, -y, +z, -z): the same
  /// bits wherever it is called.
  template <class V>
  double neighbour_sum_of(long c, int i, int j, int k, V&& v, double q0 = 0) const {
    const long nxy = m_mesh.nxy();
    const int nx = m_mesh.nx, ny = m_mesh.ny, nz = m_mesh.nz;
    double q = q0;
    if (i + 1 < nx) q += kx[c] * v(c + 1);
    if (i > 0) q += kx[c - 1] * v(c - 1);
    if (j + 1 < ny) q += ky[c] * v(c + nx);
    if (j > 0) q += ky[c - nx] * v(c - nx);
    if (k + 1 < nz) q += kz[c] * v(c + nxy);
    if (k > 0) q += kz[c - nxy] * v(c - nxy);
    return q;
  }

  /// The outward normal of the material's surface at cell c (i, j, k): minus the central
  /// differences of the material fraction (one-sided at the grid's border) [1/cell].
  std::array<double, 3> surface_normal(long c, int i, int j, int k) const;
  /// boundary_heat(c, tc) by the body's faces (GridProblem::face_shape): each face's own
  /// condition's heat when faces have their own (GridProblem::face_conditions), the rest split by
  /// the surface's normal (body_face_weights); sums to boundary_heat(c, tc) to round-off [W].
  FaceWeights boundary_heat_by_face(long c, int i, int j, int k, double tc) const;

 private:
  /// Conductance per unit face area [W/(m^2 K)] between neighbouring material cells a and b.
  double face_conductance_per_area(long a, long b) const;
  /// The boundary terms {q0, q1} (heat q0 - q1 T [W]) of cell c's surface `area` [m^2] under
  /// condition `s` (kc: the cell's conductivity).
  std::array<double, 2> surface_terms(long c, const SurfaceCondition& s, double area,
                                      double kc) const;

  const GridMesh& m_mesh;
  const PhaseRelation& m_phase;
  const GridProblem& m_problem;
  const CellState& m_cells;
  const std::vector<double>& m_surface_area;
  std::vector<double> kx, ky, kz;  ///< face conductances to the +x, +y, +z neighbour [W/K]
  std::vector<double> bq0, bq1;    ///< boundary heat into the cell: bq0 - bq1 T [W]
  double m_air_diameter_m = 0;     ///< kind = air: the body's volume-equivalent diameter [m]
  SurfaceCondition m_surface;      ///< the problem's surface condition (all faces alike)
  /// With faces of their own conditions: per cell, 3 slots (a box's axes; a cylinder's ends and
  /// side) of one face's terms, and the face of each slot (kNoFace: none).
  std::vector<double> fq0, fq1;
  std::vector<std::uint8_t> fface;
  static constexpr std::uint8_t kNoFace = 255;
  const std::vector<double>* m_advected = nullptr;
};

}  // namespace thaw::sim
