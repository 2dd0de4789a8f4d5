#include "sim/grid/enthalpy_solver.h"

#include <algorithm>
#include <cmath>

#include "base/check.h"
#include "sim/grid/body_faces.h"
#include "sim/grid/cavity_drain.h"
#include "sim/grid/cell_state.h"
#include "sim/grid/conduction_operator.h"
#include "sim/grid/grid_mesh.h"
#include "sim/grid/grid_time_stepper.h"
#include "sim/grid/newton_solver.h"
#include "sim/grid/phase_relation.h"
#include "sim/grid/surface_area.h"

namespace thaw::sim {

double enthalpy_of_temperature(const Materials& m, double t_c, bool liquid) {
  const double u = t_c - m.melting_point_c;
  if (liquid) return m.latent_heat_per_volume() + m.water_heat_capacity() * std::max(u, 0.0);
  return m.ice_heat_capacity() * std::min(u, 0.0);
}

namespace {

/// The problem's fractions and enthalpies as the solver's cell state (no enthalpy in air).
CellState initial_cells(const GridProblem& p, const GridMesh& mesh) {
  THAW_CHECK(static_cast<long>(p.material_fraction.size()) == mesh.n &&
                 static_cast<long>(p.enthalpy_j_m3.size()) == mesh.n,
             "grid problem arrays must have one value per cell");
  CellState cells;
  cells.resize(mesh.n);  // every work array once, here: a step allocates nothing
  cells.m = p.material_fraction;
  cells.H = p.enthalpy_j_m3;
  for (long c = 0; c < mesh.n; ++c) {
    THAW_CHECK(cells.m[c] >= 0 && cells.m[c] <= 1 && std::isfinite(cells.H[c]),
               "material fraction outside [0, 1]");
    if (cells.m[c] == 0) cells.H[c] = 0;
  }
  return cells;
}

}  // namespace

/// The parts, built in dependency order (each holds references to the ones before it).
struct EnthalpySolver::Impl {
  GridProblem p;
  GridMesh mesh;
  PhaseRelation phase;
  CellState cells;
  CavityDrain cavity;
  SurfaceArea surface;
  ConductionOperator op;
  NewtonSolver newton;
  std::unique_ptr<GridFlow> flow;  ///< natural convection (p.flow), else null
  GridTimeStepper stepper;

  explicit Impl(GridProblem problem)
      : p(std::move(problem)),
        mesh(p.geometry, p.cells, p.origin_m, p.spacing_m),
        phase(p.materials),
        cells(initial_cells(p, mesh)),
        cavity(mesh, phase, cells, p.drain),
        surface(mesh, cells.m, cavity.exposed()),
        op(mesh, phase, p, cells, surface.area()),
        newton(mesh, phase, op, cells),
        flow(p.flow ? std::make_unique<GridFlow>(mesh, phase, p, cells, cavity.exposed())
                    : nullptr),
        stepper(p, mesh, phase, cells, cavity, surface, op, newton, flow.get()) {
    if (flow) op.set_advection(&flow->advected_w());
  }

  double liquid_volume() const {
    return sum_cells(mesh.n,
                     [&](long c) { return cells.m[c] * phase.liquid(cells.H[c]) * mesh.vol[c]; });
  }
  double ice_volume() const {
    return sum_cells(mesh.n, [&](long c) { return cavity.ice_fraction(c) * mesh.vol[c]; });
  }

  GridSnapshot snapshot() const {
    GridSnapshot out;
    out.time_s = stepper.time();
    out.liquid_volume_m3 = liquid_volume();
    out.ice_volume_m3 = ice_volume();
    out.enclosed_liquid_volume_m3 = cavity.enclosed_liquid_volume();
    out.held_water_m3 = cavity.held_water_volume();
    out.water_level_m = cavity.water_level_m();
    out.drained_m3 = stepper.drained_volume();
    out.enthalpy_j = stepper.energy();
    out.heat_in_j = stepper.heat_in();
    out.drained_j = stepper.drained();
    out.face_heat_in_j = stepper.face_heat_in();
    out.energy_balance_error = std::abs(out.enthalpy_j - stepper.initial_energy() -
                                        stepper.heat_in() + stepper.drained()) /
                               stepper.reference_energy();
    if (flow) {
      out.max_speed_m_s = flow->max_speed_m_s();
      out.rayleigh = flow->rayleigh();
    }
    return out;
  }

  GridField field() const {
    GridField f;
    f.geometry = p.geometry;
    f.cells = p.cells;
    f.origin_m = p.origin_m;
    f.spacing_m = mesh.dx_m;
    f.time_s = stepper.time();
    const auto n = static_cast<std::size_t>(mesh.n);
    f.temperature_c.resize(n);
    f.ice_fraction.resize(n);
    f.water_fraction.resize(n);
    for (std::size_t c = 0; c < n; ++c) {
      const double m = cells.m[c], H = cells.H[c];
      // air cells show the temperature of the surrounding air / held surface
      f.temperature_c[c] =
          static_cast<float>(m > 0 ? phase.temperature(H) : p.surface_temperature_c);
      const double liq = phase.liquid(H);
      f.water_fraction[c] = static_cast<float>(m * liq);
      f.ice_fraction[c] = static_cast<float>(std::min(m * (1 - liq), 1.0 - f.water_fraction[c]));
    }
    if (flow) {
      // The flow's face velocities averaged to the cell centres (axisymmetric: u_r, u_y, 0).
      f.velocity_m_s.resize(3 * n);
      for (int k = 0; k < f.cells[2]; ++k)
        for (int j = 0; j < f.cells[1]; ++j)
          for (int i = 0; i < f.cells[0]; ++i)
            for (int d = 0; d < 3; ++d)
              f.velocity_m_s[3 * f.index(i, j, k) + static_cast<std::size_t>(d)] =
                  static_cast<float>(flow->cell_velocity_m_s(d, i, j, k));
    }
    return f;
  }
};

EnthalpySolver::EnthalpySolver(GridProblem problem)
    : m_impl(std::make_unique<Impl>(std::move(problem))) {}
EnthalpySolver::~EnthalpySolver() = default;
double EnthalpySolver::advance_to(double t_target, const std::function<bool()>& stop) {
  return m_impl->stepper.advance_to(t_target, stop);
}
double EnthalpySolver::time() const {
  return m_impl->stepper.time();
}
bool EnthalpySolver::finished() const {
  return m_impl->stepper.done();
}
GridSnapshot EnthalpySolver::snapshot() const {
  return m_impl->snapshot();
}
GridField EnthalpySolver::field() const {
  return m_impl->field();
}
std::vector<std::string> EnthalpySolver::face_names() const {
  return body_face_names(m_impl->p.face_shape);
}
const std::vector<GridEvent>& EnthalpySolver::events() const {
  return m_impl->stepper.events();
}
const GridStatistics& EnthalpySolver::statistics() const {
  return m_impl->stepper.statistics();
}
double EnthalpySolver::reference_energy() const {
  return m_impl->stepper.reference_energy();
}
std::vector<double> EnthalpySolver::liquid_fraction() const {
  const Impl& s = *m_impl;
  std::vector<double> out(static_cast<std::size_t>(s.mesh.n));
  for (long c = 0; c < s.mesh.n; ++c) out[c] = s.cells.m[c] * s.phase.liquid(s.cells.H[c]);
  return out;
}
const std::vector<double>& EnthalpySolver::material_fraction() const {
  return m_impl->cells.m;
}
const std::vector<double>& EnthalpySolver::enthalpy() const {
  return m_impl->cells.H;
}
double EnthalpySolver::cell_volume(int i, int j, int k) const {
  const GridMesh& g = m_impl->mesh;
  return g.vol[i + static_cast<long>(g.nx) * (j + static_cast<long>(g.ny) * k)];
}

}  // namespace thaw::sim
