#pragma once
// The planar two-phase Neumann similarity solution of the Stefan problem (Carslaw & Jaeger,
// "Conduction of Heat in Solids", 2nd ed., sec. 11.2; Crank, "Free and Moving Boundary
// Problems", sec. 1.3): a half-space x > 0 of phase 2, initially at T_far, whose face x = 0 is
// held from t = 0 at T_face; phase 1 grows from the face, front at T_m, s(t) = 2 lambda
// sqrt(alpha_1 t). Covers melting (phase 1 = water, T_face > T_m >= T_far) and freezing
// (phase 1 = ice, T_face < T_m <= T_far). Used as the validation reference and as the exact
// small-time start of a phase of zero initial thickness. Knows nothing of the solver.

namespace thaw::sim {

struct NeumannSolution {
  double k1 = 0,
         heat_capacity1 = 0;  ///< phase 1 (adjacent to the face): k [W/(m K)], rho c [J/(m^3 K)]
  double k2 = 0, heat_capacity2 = 0;  ///< phase 2 (far field)
  double latent_heat_per_volume = 0;  ///< L_v [J/m^3]
  double face_temperature = 0;        ///< T_face [C]
  double melting_point = 0;           ///< T_m [C]
  double far_temperature = 0;         ///< T_far [C]
  double lambda = 0;                  ///< root of the transcendental equation (dimensionless)

  double alpha1() const { return k1 / heat_capacity1; }
  double alpha2() const { return k2 / heat_capacity2; }
  /// Front position s(t) = 2 lambda sqrt(alpha_1 t) [m].
  double front(double t_s) const;
  /// Front speed ds/dt [m/s] (t > 0).
  double front_speed(double t_s) const;
  /// Time at which the front reaches s [s].
  double time_of_front(double s_m) const;
  /// Temperature T(x, t) [C] for x >= 0, t > 0.
  double temperature(double x_m, double t_s) const;
  /// Heat entering the half-space through the face per unit area, -k1 dT/dx(0, t) [W/m^2].
  double face_heat_flux(double t_s) const;
  /// Heat entered through the face per unit area during [0, t] [J/m^2].
  double face_heat(double t_s) const;
};

/// Solves  St1 exp(-l^2)/erf(l) - St2 exp(-nu^2 l^2)/(nu erfc(nu l)) = l sqrt(pi)  for l by
/// bisection to round-off, with St1 = C1 |T_face - T_m| / L_v, St2 = C2 |T_m - T_far| / L_v and
/// nu = sqrt(alpha1 / alpha2). Requires T_face and T_far on opposite sides of (or at) T_m and
/// T_face != T_m.
NeumannSolution solve_neumann(double k1, double heat_capacity1, double k2, double heat_capacity2,
                              double latent_heat_per_volume, double face_temperature,
                              double melting_point, double far_temperature);

}  // namespace thaw::sim
