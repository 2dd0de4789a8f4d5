#pragma once
// Planar two-phase Neumann problems run inside the grid enthalpy solver, shared by its unit tests
// (test_enthalpy_solver.cpp) and the full study (test_enthalpy_solver_e2e.cpp): the exact
// problem (melting or freezing, any materials), its grid problem along any axis started from the
// exact cell averages at t0, a run to t1 with the front sampled on the way, and the exact heat and
// enthalpy change computed independently of the solver.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "sim/format/scenario_file.h"
#include "sim/grid/enthalpy_solver.h"
#include "sim/reference/neumann.h"

namespace thaw::sim::test {

using Geo = GridField::Geometry;

/// Gauss-Legendre, 8 points on [lo, hi] (exact for polynomials of degree 15).
inline double gauss8(const std::function<double(double)>& f, double lo, double hi) {
  static const double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                              0.9602898564975363};
  static const double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                              0.1012285362903763};
  double sum = 0;
  for (int q = 0; q < 4; ++q)
    for (int sign : {-1, 1}) sum += w[q] * f(0.5 * (lo + hi) + sign * 0.5 * (hi - lo) * x[q]);
  return 0.5 * sum * (hi - lo);
}

/// Phase 1 grows from a face x = 0 held at T_face into phase 2, initially at T_far: melting
/// (phase 1 = water) or freezing (phase 1 = ice). Started at t0 from the exact profile, compared
/// on the way to t1.
struct PlanarNeumann {
  std::string name;
  Materials mat;
  bool melting = false;
  double face_c = 0, far_c = 0;
  double t0 = 100, t1 = 400;
  NeumannSolution exact;
  double length = 0;  ///< face to far wall [m]

  PlanarNeumann(std::string n, const Materials& m, bool melt, double face, double far)
      : name(std::move(n)), mat(m), melting(melt), face_c(face), far_c(far) {
    const double kw = mat.water_conductivity_w_mk, cw = mat.water_heat_capacity();
    const double ki = mat.ice_conductivity_w_mk, ci = mat.ice_heat_capacity();
    const double lv = mat.latent_heat_per_volume(), tm = mat.melting_point_c;
    exact = melting ? solve_neumann(kw, cw, ki, ci, lv, face_c, tm, far_c)
                    : solve_neumann(ki, ci, kw, cw, lv, face_c, tm, far_c);
    // Far phase at T_m: it stays at T_m (no thermal layer), so an insulated far wall a quarter
    // of the front beyond the front at t1 is exact. Otherwise the far wall is held at T_far six
    // thermal lengths sqrt(alpha_2 t1) beyond the front, where the exact solution differs from
    // T_far by erfc(3) / erfc(nu lambda) ~ 2e-5 of the far excess (and the heat through that
    // wall is counted on both sides of the comparison, exact_heat_per_area()).
    length = far_held() ? exact.front(t1) + 6.0 * std::sqrt(exact.alpha2() * t1)
                        : 1.25 * exact.front(t1);
  }
  bool far_held() const { return far_c != mat.melting_point_c; }
  /// Stefan numbers C |dT| / L_v of the growing (1) and the far (2) phase.
  double stefan1() const {
    return (melting ? mat.water_heat_capacity() : mat.ice_heat_capacity()) *
           std::abs(face_c - mat.melting_point_c) / mat.latent_heat_per_volume();
  }
  double stefan2() const {
    return (melting ? mat.ice_heat_capacity() : mat.water_heat_capacity()) *
           std::abs(far_c - mat.melting_point_c) / mat.latent_heat_per_volume();
  }
  /// Exact enthalpy per unit volume [J/m^3] at depth x, time t (relative to ice at T_m).
  double enthalpy(double x, double t) const {
    const bool in1 = x < exact.front(t);
    return enthalpy_of_temperature(mat, exact.temperature(x, t), in1 == melting);
  }
  /// Integral of the exact enthalpy over [a, b] at time t [J/m^2], split at the front so the
  /// latent jump is integrated exactly, 4 Gauss panels per piece (the profile is smooth on
  /// each piece: the quadrature error is far below the solver's).
  double enthalpy_integral(double a, double b, double t) const {
    auto piece = [&](double lo, double hi) {
      double sum = 0;
      for (int k = 0; k < 4; ++k)
        sum += gauss8([&](double x) { return enthalpy(x, t); }, lo + (hi - lo) * k / 4,
                      lo + (hi - lo) * (k + 1) / 4);
      return sum;
    };
    const double s = exact.front(t);
    if (s > a && s < b) return piece(a, s) + piece(s, b);
    return piece(a, b);
  }
  /// Exact change of the total enthalpy (sensible + latent) over [0, length] from t0 to t1.
  double exact_enthalpy_change() const {
    return enthalpy_integral(0, length, t1) - enthalpy_integral(0, length, t0);
  }
  /// Heat per unit area that entered through both walls during [t0, t1] [J/m^2], from the
  /// exact temperature's gradient at x = 0 and x = length by finite differences (independent
  /// of the closed form NeumannSolution::face_heat_flux and of the solver), integrated in time
  /// by Gauss panels in u = sqrt(t) (the face flux ~ t^-1/2 is smooth in u).
  double exact_heat_per_area() const {
    auto flux = [&](double t) {
      // second-order one-sided difference at the face (T is smooth on [0, s)), central at the
      // far wall, step 1e-4 of the front: relative error ~ (1e-4)^2 of T''' / T', ~1e-8.
      const double h = 1e-4 * exact.front(t);
      const double g0 = (-3 * exact.temperature(0, t) + 4 * exact.temperature(h, t) -
                         exact.temperature(2 * h, t)) /
                        (2 * h);
      const double gl =
          (exact.temperature(length + h, t) - exact.temperature(length - h, t)) / (2 * h);
      return -exact.k1 * g0 + (far_held() ? exact.k2 * gl : 0.0);
    };
    double sum = 0;
    const double u0 = std::sqrt(t0), u1 = std::sqrt(t1);
    for (int k = 0; k < 8; ++k)
      sum += gauss8([&](double u) { return flux(u * u) * 2 * u; }, u0 + (u1 - u0) * k / 8,
                    u0 + (u1 - u0) * (k + 1) / 8);
    return sum;
  }

  /// The problem along `axis` (0 = x, 1 = y, 2 = z; axisymmetric grids: y only) of an n-cell
  /// line, `across` cells across, constant steps dt; cells hold the exact averages at t0.
  GridProblem problem(Geo g, int axis, int n, int across, double dt) const {
    GridProblem p;
    p.geometry = g;
    p.spacing_m = length / n;
    p.cells = {across, across, g == Geo::axisymmetric ? 1 : across};
    p.cells[axis] = n;
    p.materials = mat;
    p.drain = false;
    p.fixed_step_s = dt;
    p.walls[2 * axis] = {true, face_c};
    p.walls[2 * axis + 1] = {far_held(), far_c};
    const std::size_t nxy = static_cast<std::size_t>(p.cells[0]) * p.cells[1];
    const std::size_t cells = nxy * p.cells[2];
    p.material_fraction.assign(cells, 1.0);
    p.enthalpy_j_m3.resize(cells);
    std::vector<double> line(n);
    for (int j = 0; j < n; ++j)
      line[j] = enthalpy_integral(j * p.spacing_m, (j + 1) * p.spacing_m, t0) / p.spacing_m;
    for (std::size_t c = 0; c < cells; ++c) {
      const std::size_t ijk[3] = {c % p.cells[0], (c / p.cells[0]) % p.cells[1], c / nxy};
      p.enthalpy_j_m3[c] = line[ijk[axis]];
    }
    return p;
  }
};

struct NeumannRun {
  double front = 0;        ///< phase-1 volume / cross-section at t1 [m]
  double front_error = 0;  ///< largest |front - exact| / exact over 16 instants in (t0, t1]
  double heat = 0;         ///< solver's heat in per unit area over [t0, t1] [J/m^2]
  double enthalpy = 0;     ///< solver's enthalpy change per unit area over [t0, t1] [J/m^2]
  double step_energy = 0;  ///< largest per-step energy error (relative, the solver's own)
  std::vector<double> final_enthalpy;  ///< every cell's enthalpy at t1 [J/m^3]
};

inline NeumannRun run_planar_neumann(const PlanarNeumann& pn, Geo g, int axis, int n, int across,
                                     double dt) {
  EnthalpySolver solver(pn.problem(g, axis, n, across, dt));
  const double e0 = solver.snapshot().enthalpy_j;
  // cross-section: the cells of the first layer along the axis, over the cell size
  double area = 0;
  const int a1 = axis == 0 ? 1 : 0, a2 = axis == 2 ? 1 : 2;
  for (int u = 0; u < across; ++u)
    for (int v = 0; v < (g == Geo::axisymmetric ? 1 : across); ++v) {
      int ijk[3] = {0, 0, 0};
      ijk[a1] = u;
      ijk[a2] = v;
      area += solver.cell_volume(ijk[0], ijk[1], ijk[2]) / (pn.length / n);
    }
  NeumannRun r;
  // The enthalpy method's front error oscillates as the front crosses cells, so one instant
  // can fall near a zero of it: the error is the largest over 16 instants in (t0, t1] (the
  // solver's clock starts at 0).
  for (int q = 1; q <= 16; ++q) {
    const double t = pn.t0 + (pn.t1 - pn.t0) * q / 16;
    solver.advance_to(t - pn.t0);
    const GridSnapshot s = solver.snapshot();
    r.front = (pn.melting ? s.liquid_volume_m3 : s.ice_volume_m3) / area;
    r.front_error =
        std::max(r.front_error, std::abs(r.front - pn.exact.front(t)) / pn.exact.front(t));
  }
  const GridSnapshot snap = solver.snapshot();
  r.heat = snap.heat_in_j / area;
  r.enthalpy = (snap.enthalpy_j - e0) / area;
  r.step_energy = solver.statistics().max_step_energy_error;
  r.final_enthalpy = solver.enthalpy();
  return r;
}

/// Materials with every property of the two phases different and the conductivity contrast of
/// ice and water reversed (water conducts 4x better than ice; rho, c and so alpha differ too),
/// so a conductivity or heat capacity taken from the wrong phase anywhere near the front
/// changes the answer at O(1).
inline Materials reversed_materials() {
  Materials m;
  m.ice_conductivity_w_mk = 0.5;
  m.ice_density_kg_m3 = 900;
  m.ice_specific_heat_j_kgk = 1500;
  m.water_conductivity_w_mk = 2.0;
  m.water_density_kg_m3 = 1100;
  m.water_specific_heat_j_kgk = 3600;
  m.latent_heat_j_kg = 300000;
  m.melting_point_c = 0;
  return m;
}

/// Observed errors at three resolutions (the front resolved by 8, 16, 32 cells at t1).
struct NeumannStudy {
  double front[3] = {0, 0, 0}, heat[3] = {0, 0, 0}, enthalpy[3] = {0, 0, 0};
  double heat_vs_enthalpy = 0;  ///< largest |solver heat - solver dH| / |exact heat|
  double step_energy = 0;       ///< largest per-step energy error of the three runs
  double exact_identity = 0;    ///< |exact heat - exact dH| / |exact heat|
  static double order(const double e[3]) { return std::log2(e[0] / e[2]) / 2; }
  static double pair_order(const double e[3], int i) { return std::log2(e[i] / e[i + 1]); }
};

/// Runs `pn` in grid `g` along `axis` at three resolutions; dt = alpha_1-diffusion time of a
/// quarter cell, so Backward Euler's O(dt) error is O(dx^2) and the spatial order shows.
inline NeumannStudy study_planar_neumann(const PlanarNeumann& pn, Geo g, int axis = 1) {
  NeumannStudy st;
  const double front = pn.exact.front(pn.t1);
  const double heat = pn.exact_heat_per_area(), dh = pn.exact_enthalpy_change();
  st.exact_identity = std::abs(heat - dh) / std::abs(heat);
  std::printf("%s %s: St1 %.3g St2 %.3g lambda %.4f front(t1) %.4g m, length %.4g m\n",
              g == Geo::axisymmetric ? "axisymmetric" : "3d", pn.name.c_str(), pn.stefan1(),
              pn.stefan2(), pn.exact.lambda, front, pn.length);
  const int cells_per_front[3] = {8, 16, 32};
  for (int i = 0; i < 3; ++i) {
    const int n = static_cast<int>(std::ceil(cells_per_front[i] * pn.length / front));
    const double dx = pn.length / n;
    const double dt = 0.25 * dx * dx / pn.exact.alpha1();
    const NeumannRun r = run_planar_neumann(pn, g, axis, n, 1, dt);
    st.front[i] = r.front_error;
    st.heat[i] = std::abs(r.heat - heat) / std::abs(heat);
    st.enthalpy[i] = std::abs(r.enthalpy - dh) / std::abs(dh);
    st.heat_vs_enthalpy =
        std::max(st.heat_vs_enthalpy, std::abs(r.heat - r.enthalpy) / std::abs(heat));
    st.step_energy = std::max(st.step_energy, r.step_energy);
    std::printf("  n=%4d dx=%.3g m: front %.3e, heat %.3e, dH %.3e (relative), step energy %.1e\n",
                n, dx, st.front[i], st.heat[i], st.enthalpy[i], r.step_energy);
  }
  std::printf("  orders: front %.2f %.2f (mean %.2f), heat %.2f %.2f (mean %.2f)\n",
              NeumannStudy::pair_order(st.front, 0), NeumannStudy::pair_order(st.front, 1),
              NeumannStudy::order(st.front), NeumannStudy::pair_order(st.heat, 0),
              NeumannStudy::pair_order(st.heat, 1), NeumannStudy::order(st.heat));
  return st;
}

}  // namespace thaw::sim::test
