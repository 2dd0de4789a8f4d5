// Prints the convergence tables of docs/validation.md: observed orders of the front position
// (and temperature profile) in space and in time for the planar Neumann problems, the
// small-Stefan-number limits of inward freezing, the melting-point cavity, and the default
// scenario's accuracy against a 16x finer run. Usage: sim_convergence [--quick]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "sim/format/scenario_file.h"
#include "sim/simulate.h"
#include "sim/stefan1d/neumann_problem.h"

using namespace thaw::sim;

namespace {

struct Case {
  bool melting;
  double face, far;
};
const Case kCases[] = {{true, 10, 5}, {true, 40, 10}, {false, 10, 3}, {false, 30, 0}};

NeumannProblem problem(const Case& c, int cells, double tol, double fixed) {
  NeumannProblem p;
  p.melting = c.melting;
  p.face_excess_k = c.face;
  p.far_excess_k = c.far;
  p.cells_per_phase = cells;
  p.time_tolerance = tol;
  p.fixed_step_s = fixed;
  return p;
}

double order(double coarse, double fine) {
  return coarse > 0 && fine > 0 ? std::log2(coarse / fine) : NAN;
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const Materials m;
  std::printf(
      "## Space: planar Neumann problems, t0 = 100 s -> t1 = 1000 s, time tolerance 1e-11\n\n");
  std::printf(
      "| case | St_face | St_far | cells/phase | front rel. error | order | max T error [K] | "
      "order |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const Case& c : kCases) {
    const double cf = c.melting ? m.water_heat_capacity() : m.ice_heat_capacity();
    const double cr = c.melting ? m.ice_heat_capacity() : m.water_heat_capacity();
    double pe = 0, pt = 0;
    for (int n : quick ? std::vector<int>{20, 40, 80} : std::vector<int>{20, 40, 80, 160, 320}) {
      const auto r = run_neumann_problem(problem(c, n, 1e-11, 0));
      const double e = r.relative_front_error();
      std::printf("| %s %g/%g K | %.3f | %.3f | %d | %.3e | %.2f | %.3e | %.2f |\n",
                  c.melting ? "melt" : "freeze", c.face, c.far,
                  cf * c.face / m.latent_heat_per_volume(), cr * c.far / m.latent_heat_per_volume(),
                  n, e, order(pe, e), r.temperature_error_k, order(pt, r.temperature_error_k));
      pe = e;
      pt = r.temperature_error_k;
    }
  }
  std::printf(
      "\n## Time: constant steps, 40 cells/phase, error against 2048 steps on the same grid\n\n");
  std::printf("| case | steps | front rel. error | order |\n|---|---|---|---|\n");
  for (const Case& c : kCases) {
    const double ref = run_neumann_problem(problem(c, 40, 1e-6, 900.0 / 2048)).front_m;
    double pe = 0;
    for (int k : quick ? std::vector<int>{8, 16, 32} : std::vector<int>{8, 16, 32, 64, 128}) {
      const auto r = run_neumann_problem(problem(c, 40, 1e-6, 900.0 / k));
      const double e = std::abs(r.front_m - ref) / r.exact_front_m;
      std::printf("| %s %g/%g K | %d | %.3e | %.2f |\n", c.melting ? "melt" : "freeze", c.face,
                  c.far, k, e, order(pe, e));
      pe = e;
    }
  }

  std::printf(
      "\n## Zero-thickness starts against Neumann at 600 s (planar, time tolerance 1e-10)\n\n");
  std::printf(
      "| cells/phase | no ice yet: water 3 C, face -10 C | order | no water yet: ice -5 C, face 20 "
      "C | order |\n");
  std::printf("|---|---|---|---|---|\n");
  {
    NeumannProblem freeze;
    freeze.melting = false;
    freeze.face_excess_k = 10;
    freeze.far_excess_k = 3;
    NeumannProblem melt;
    melt.face_excess_k = 20;
    melt.far_excess_k = 5;
    const double exact_freeze = neumann_solution(freeze).front(600),
                 exact_melt = neumann_solution(melt).front(600);
    double pf = 0, pm = 0;
    for (int n : quick ? std::vector<int>{20, 40, 80} : std::vector<int>{20, 40, 80, 160, 320}) {
      Scenario a;  // water slab 100 mm (10 thermal lengths of water at 600 s), no ice
      a.geometry = Geometry::planar;
      a.inner_radius_m = a.outer_radius_m = 0.1;
      a.water_initial_temperature_c = 3;
      a.ice_initial_temperature_c = 0;
      a.outer_kind = OuterBoundary::temperature;
      a.outer_temperature_c = -10;
      a.duration_s = a.output_interval_s = 600;
      a.cells_per_phase = n;
      a.time_tolerance = 1e-10;
      FrontFixingSolver sa(a);
      sa.advance_to(600);
      const double ef =
          std::abs(0.1 - sa.snapshot(false).inner_radius_m - exact_freeze) / exact_freeze;
      Scenario b;  // ice slab 300 mm (10 thermal lengths of ice), no water, face held at 20 C
      b.geometry = Geometry::planar;
      b.inner_kind = InnerBoundary::temperature;
      b.inner_temperature_c = 20;
      b.inner_radius_m = 0;
      b.outer_radius_m = 0.3;
      b.ice_initial_temperature_c = -5;
      b.water_initial_temperature_c = 20;
      b.outer_kind = OuterBoundary::insulated;
      b.duration_s = b.output_interval_s = 600;
      b.cells_per_phase = n;
      b.time_tolerance = 1e-10;
      FrontFixingSolver sb(b);
      sb.advance_to(600);
      const double em = std::abs(sb.snapshot(false).inner_radius_m - exact_melt) / exact_melt;
      std::printf("| %d | %.3e | %.2f | %.3e | %.2f |\n", n, ef, order(pf, ef), em, order(pm, em));
      pf = ef;
      pm = em;
    }
  }

  std::printf(
      "\n## Inward freezing of water at T_m, surface held at T_m - dT (zero initial ice), 128 "
      "cells\n\n");
  std::printf(
      "| geometry | St | t_f / t_quasi-steady | (t_f/t_qs - 1) / St |\n|---|---|---|---|\n");
  for (Geometry g : {Geometry::cylinder, Geometry::sphere})
    for (double st : {0.04, 0.02, 0.01, 0.005}) {
      Scenario sc;
      sc.geometry = g;
      const double r = 0.01, dt = st * m.latent_heat_per_volume() / m.ice_heat_capacity();
      const double alpha = m.ice_conductivity_w_mk / m.ice_heat_capacity();
      const double t_qs = r * r / ((g == Geometry::sphere ? 6 : 4) * st * alpha);
      sc.inner_radius_m = sc.outer_radius_m = r;
      sc.water_initial_temperature_c = sc.ice_initial_temperature_c = 0;
      sc.outer_kind = OuterBoundary::temperature;
      sc.outer_temperature_c = -dt;
      sc.duration_s = sc.output_interval_s = 1.5 * t_qs;
      sc.cells_per_phase = 128;
      sc.time_tolerance = 1e-10;
      FrontFixingSolver solver(sc);
      solver.advance_to(sc.duration_s);
      double t_f = NAN;
      for (const Event& e : solver.events())
        if (e.kind == "core_frozen") t_f = e.time_s;
      std::printf("| %s | %g | %.6f | %.3f |\n", to_string(g), st, t_f / t_qs,
                  (t_f / t_qs - 1) / st);
    }

  std::printf(
      "\n## Warm water in a cavity of ice at T_m (sphere, s0 = 5 mm, insulated), after 3000 s\n\n");
  std::printf("| water excess [K] | St | s_final / (s0 (1+St)^(1/3)) - 1 |\n|---|---|---|\n");
  for (double dt : {5.0, 20.0, 60.0}) {
    Scenario sc;
    sc.inner_radius_m = 0.005;
    sc.outer_radius_m = 0.01;
    sc.water_initial_temperature_c = dt;
    sc.ice_initial_temperature_c = 0;
    sc.outer_kind = OuterBoundary::insulated;
    sc.duration_s = sc.output_interval_s = 3000;
    sc.cells_per_phase = 24;
    FrontFixingSolver solver(sc);
    solver.advance_to(3000);
    const double st = m.water_heat_capacity() * dt / m.latent_heat_per_volume();
    std::printf("| %g | %.4f | %.2e |\n", dt, st,
                solver.snapshot(false).inner_radius_m / (0.005 * std::cbrt(1 + st)) - 1);
  }

  std::printf("\n## Default scenario against finer runs (cells x f, time tolerance / f^3)\n\n");
  std::printf(
      "| refinement f | cells/phase | steps | wall [ms] | break-through [s] | max rel. front error "
      "vs 16x |\n");
  std::printf("|---|---|---|---|---|---|\n");
  const Scenario base = default_scenario();
  auto refined = [&](int f) {
    Scenario s = base;
    s.cells_per_phase *= f;
    s.time_tolerance /= static_cast<double>(f) * f * f;
    return s;
  };
  const SimulationResult ref = simulate(refined(16));
  for (int f : {1, 2, 4}) {
    const auto start = std::chrono::steady_clock::now();
    const SimulationResult r = simulate(refined(f));
    const double ms =
        1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    double err = 0;
    for (std::size_t i = 0; i < r.snapshots.size() && i < ref.snapshots.size(); ++i) {
      if (r.snapshots[i].time_s != ref.snapshots[i].time_s) break;
      err = std::max(err,
                     std::abs(r.snapshots[i].inner_radius_m / ref.snapshots[i].inner_radius_m - 1));
      err = std::max(err,
                     std::abs(r.snapshots[i].outer_radius_m / ref.snapshots[i].outer_radius_m - 1));
    }
    std::printf("| %d | %d | %ld | %.1f | %.4f | %.2e |\n", f, base.cells_per_phase * f,
                r.statistics.steps, ms, r.events.back().time_s, err);
  }
  std::printf("| 16 (reference) | %d | %ld | | %.4f | |\n", base.cells_per_phase * 16,
              ref.statistics.steps, ref.events.back().time_s);
  return 0;
}
