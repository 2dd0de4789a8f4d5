#include "sim/stefan1d/neumann_problem.h"

#include <algorithm>
#include <cmath>

#include "sim/scenario/scenario_rules.h"

namespace thaw::sim {

NeumannSolution neumann_solution(const NeumannProblem& p) {
  const Materials& m = p.materials;
  const double tm = m.melting_point_c;
  return p.melting ? solve_neumann(m.water_conductivity_w_mk, m.water_heat_capacity(),
                                   m.ice_conductivity_w_mk, m.ice_heat_capacity(),
                                   m.latent_heat_per_volume(), tm + p.face_excess_k, tm,
                                   tm - p.far_excess_k)
                   : solve_neumann(m.ice_conductivity_w_mk, m.ice_heat_capacity(),
                                   m.water_conductivity_w_mk, m.water_heat_capacity(),
                                   m.latent_heat_per_volume(), tm - p.face_excess_k, tm,
                                   tm + p.far_excess_k);
}

NeumannComparison run_neumann_problem(const NeumannProblem& p) {
  const NeumannSolution ne = neumann_solution(p);
  const double tm = p.materials.melting_point_c;
  // The exact far field differs from T_far by erfc(d / (2 sqrt(alpha t1))) of the far excess at
  // distance d beyond the front: with d = 10 sqrt(alpha t1), erfc(5) = 1.5e-12, so holding T_far
  // (or a symmetry plane) there is exact to round-off (at 6 lengths it would be erfc(3) = 2e-5,
  // ~1e-4 K, visible in the profile errors at 320 cells).
  const double far =
      ne.front(p.t1_s) + 10 * std::sqrt(ne.alpha2() * p.t1_s);  // alpha of the far phase
  Scenario sc;
  sc.geometry = Geometry::planar;
  sc.materials = p.materials;
  sc.duration_s = p.t1_s;
  sc.output_interval_s = p.t1_s;
  sc.cells_per_phase = p.cells_per_phase;
  sc.time_tolerance = p.time_tolerance;
  sc.outer_kind = OuterBoundary::temperature;
  sc.outer_radius_m = far;
  // position measured from the face: melting face at x = 0 (inner wall), freezing face at x = far
  auto from_face = [&](double x) { return p.melting ? x : far - x; };
  if (p.melting) {
    sc.inner_kind = InnerBoundary::temperature;
    sc.inner_temperature_c = tm + p.face_excess_k;
    sc.inner_radius_m = ne.front(p.t0_s);
    sc.outer_temperature_c = tm - p.far_excess_k;
    sc.water_initial_temperature_c = tm + p.face_excess_k;
    sc.ice_initial_temperature_c = tm - p.far_excess_k;
  } else {
    sc.inner_radius_m = far - ne.front(p.t0_s);
    sc.outer_temperature_c = tm - p.face_excess_k;
    sc.water_initial_temperature_c = tm + p.far_excess_k;
    sc.ice_initial_temperature_c = tm - p.face_excess_k;
  }
  SolverOptions opt;
  opt.fixed_step_s = p.fixed_step_s;
  opt.start_time_s = p.t0_s;
  opt.initial_temperature_c = [&](double x) { return ne.temperature(from_face(x), p.t0_s); };
  validate_scenario(sc, "neumann problem");
  FrontFixingSolver solver(sc, opt);
  solver.advance_to(p.t1_s);
  const Snapshot snap = solver.snapshot(true);
  NeumannComparison c;
  c.front_m = from_face(snap.inner_radius_m);
  c.exact_front_m = ne.front(p.t1_s);
  for (const ProfilePoint& pt : snap.profile)
    c.temperature_error_k =
        std::max(c.temperature_error_k,
                 std::abs(pt.temperature_c - ne.temperature(from_face(pt.r_m), p.t1_s)));
  c.energy_balance_error = snap.energy_balance_error;
  c.heat_in_j = snap.heat_in_j;
  c.steps = solver.statistics().steps;
  return c;
}

}  // namespace thaw::sim
