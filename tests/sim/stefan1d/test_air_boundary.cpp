// The 1D solver under [outer_boundary] kind = "air" (sim/boundary/air_model.h): the free ice
// sphere against the model's own melt-time integral, and the melt onset of cold ice against an
// independent solution of the nonlinear surface problem (a Volterra integral equation), so the
// surface-temperature-dependent flux is shown to be solved with the cells, not lagged.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "sim/boundary/air_model.h"
#include "sim/boundary/scenario_air.h"
#include "sim/scenario/scenario_rules.h"
#include "sim/stefan1d/front_fixing.h"

namespace thaw::sim {
namespace {

const Materials kMat{};

Scenario free_sphere(double speed, double humidity, double surroundings_c) {
  Scenario sc;
  sc.geometry = Geometry::sphere;
  sc.materials = kMat;
  sc.inner_radius_m = 0.0;
  sc.outer_radius_m = 0.02;
  sc.ice_initial_temperature_c = 0.0;
  sc.water_initial_temperature_c = 0.0;
  sc.outer_kind = OuterBoundary::air;
  sc.outer_temperature_c = 20.0;
  sc.relative_humidity = humidity;
  sc.air_speed_m_s = speed;
  sc.surroundings_temperature_c = surroundings_c;
  sc.duration_s = 40000;
  sc.output_interval_s = 1000;
  sc.cells_per_phase = 16;
  return sc;
}

double event_time(const FrontFixingSolver& solver, const char* kind) {
  for (const Event& e : solver.events())
    if (e.kind == kind) return e.time_s;
  return -1;
}

TEST(AirBoundary, FreeIceSphereMeltsInTheModelsMeltTime) {
  // Ice at T_m everywhere: the surface ablates from t = 0 and all the air's heat melts ice, so
  // rho_i L db/dt = -q(2b) and t_melt = rho_i L integral_0^b0 db / q(2b), here by the midpoint
  // rule on 20000 intervals (error ~1e-8). The solver integrates the same ODE by TR-BDF2 under
  // time_tolerance 1e-6 per step on b: the time error is at most steps * 1e-6 relative.
  const double humid = 0.5;
  const double neutral = saturation_vapour_pressure_pa(0.0) / saturation_vapour_pressure_pa(20.0) *
                         293.15 / 273.15;  // vapour density of saturation at 0 C: no latent heat
  struct Case {
    double speed, humidity, surroundings_c, hours;  // hours: docs/validation.md's figure
  };
  for (const Case& c :
       {Case{0, neutral, 0, 8.48}, Case{0, neutral, 20, 5.47}, Case{0, humid, 20, 4.28},
        Case{2, neutral, 0, 2.03}, Case{2, humid, 20, 1.30}}) {
    const Scenario sc = free_sphere(c.speed, c.humidity, c.surroundings_c);
    validate_scenario(sc);
    const Air air = scenario_air(sc);
    double t_ref = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const double b = 0.02 * (i + 0.5) / n;
      t_ref += kMat.latent_heat_per_volume() * (0.02 / n) /
               air_heat_flux(air, radial_air_body(sc, b), 0.0).total_w_m2();
    }
    FrontFixingSolver solver(sc);
    solver.advance_to(sc.duration_s);
    ASSERT_TRUE(solver.finished());
    const double t = event_time(solver, "fully_melted");
    std::printf("  %g m/s, RH %.3f, T_sur %g C: melted at %.1f s (%.3f h), integral %.1f s\n",
                c.speed, c.humidity, c.surroundings_c, t, t / 3600, t_ref);
    EXPECT_NEAR(t, t_ref, solver.statistics().steps * sc.time_tolerance * t_ref);
    EXPECT_NEAR(t / 3600, c.hours, 0.005);
    EXPECT_LT(solver.snapshot(false).energy_balance_error, 1e-10);
  }
}

/// Melt onset of a semi-infinite ice block at T_i under the air's flux q(T_s): the surface
/// temperature obeys the Volterra equation (Carslaw & Jaeger sec. 2.5, Duhamel)
///   T_s(t) = T_i + integral_0^t q(T_s(tau)) / sqrt(pi k rho c (t - tau)) dtau,
/// solved by product integration with q linear on each interval (weights exact for the kernel)
/// on a grid graded as t_j = t_end (j/N)^2 (T_s ~ sqrt(t) at first), the last q implicit by
/// bisection. Returns the time T_s reaches T_m (linear between grid points).
double volterra_onset(const Air& air, const AirBodySize& body, double ti, double t_end, int n) {
  const double c =
      1.0 / std::sqrt(std::numbers::pi * kMat.ice_conductivity_w_mk * kMat.ice_heat_capacity());
  std::vector<double> t(n + 1), q(n + 1), ts(n + 1);
  for (int j = 0; j <= n; ++j) t[j] = t_end * std::pow(double(j) / n, 2);
  ts[0] = ti;
  q[0] = air_heat_flux(air, body, ti).total_w_m2();
  for (int m = 1; m <= n; ++m) {
    // T_s(t_m) = ti + c [sum over intervals of w0 q_j + w1 q_(j+1)]
    double known = 0, w_last = 0;
    for (int j = 0; j < m; ++j) {
      const double s0 = t[m] - t[j], s1 = t[m] - t[j + 1], d = t[j + 1] - t[j];
      const double a = 2 * (std::sqrt(s0) - std::sqrt(s1));  // int s^-1/2
      const double b = (t[m] - t[j]) * a - (2.0 / 3) * (s0 * std::sqrt(s0) - s1 * std::sqrt(s1));
      const double w1 = b / d, w0 = a - w1;  // int (tau - t_j)/d s^-1/2 = b / d
      known += w0 * q[j];
      if (j + 1 < m)
        known += w1 * q[j + 1];
      else
        w_last = w1;
    }
    double lo = -100, hi = 100;
    for (int it = 0; it < 100; ++it) {
      const double mid = 0.5 * (lo + hi);
      const double f = ti + c * (known + w_last * air_heat_flux(air, body, mid).total_w_m2()) - mid;
      (f > 0 ? lo : hi) = mid;
    }
    ts[m] = 0.5 * (lo + hi);
    q[m] = air_heat_flux(air, body, ts[m]).total_w_m2();
    if (ts[m] >= 0) return t[m - 1] + (t[m] - t[m - 1]) * (0 - ts[m - 1]) / (ts[m] - ts[m - 1]);
  }
  return -1;
}

TEST(AirBoundary, MeltOnsetOfColdIceMatchesTheNonlinearSurfaceSolution) {
  // A planar ice block at -10 C, 0.8 m thick (about 10 thermal lengths sqrt(alpha t) at the
  // onset near 4700 s, so semi-infinite to ~erfc(5)), its face a 0.16 m high vertical surface in
  // still room air at 20 C, 50 %, walls at 20 C. The reference's error (second order on the
  // graded grid with 3000 intervals, ~1e-7) is far below the solver's at 80 and 160 cells.
  Scenario sc;
  sc.geometry = Geometry::planar;
  sc.materials = kMat;
  sc.inner_radius_m = 0.0;
  sc.outer_radius_m = 0.8;
  sc.lateral_size_m = 0.16;
  sc.ice_initial_temperature_c = -10.0;
  sc.water_initial_temperature_c = 0.0;
  sc.outer_kind = OuterBoundary::air;
  sc.outer_temperature_c = 20.0;
  sc.relative_humidity = 0.5;
  validate_scenario(sc);
  const double t_ref = volterra_onset(scenario_air(sc), radial_air_body(sc, 0.8), -10.0, 2e4, 3000);
  ASSERT_GT(t_ref, 0);
  auto onset = [&](int cells) {
    Scenario s = sc;
    s.cells_per_phase = cells;
    s.time_tolerance = 1e-9;
    s.duration_s = 1.5 * t_ref;
    s.output_interval_s = s.duration_s;
    FrontFixingSolver solver(s);
    solver.advance_to(s.duration_s);
    EXPECT_TRUE(solver.snapshot(false).ablating);
    EXPECT_LT(solver.snapshot(false).energy_balance_error, 1e-10);
    return event_time(solver, "melt_onset");
  };
  const double coarse = onset(80), fine = onset(160);
  std::printf("  air melt onset: %.6f / %.6f s, Volterra %.6f s\n", coarse, fine, t_ref);
  EXPECT_LE(std::abs(fine - t_ref), std::abs(coarse - fine) + 1e-6 * t_ref);
  EXPECT_LT(std::abs(fine - t_ref), 1e-3 * t_ref);
}

TEST(AirBoundary, WaterFreezesInColdAirFromZeroIce) {
  // A drop of water at T_m in air at -15 C: no ice at t = 0, the air takes heat at once, so the
  // solver starts a thin ice film whose surface balances the air (q_air(T_s) = k T_s / delta).
  Scenario sc;
  sc.geometry = Geometry::sphere;
  sc.materials = kMat;
  sc.inner_radius_m = sc.outer_radius_m = 0.005;
  sc.water_initial_temperature_c = 0.0;
  sc.ice_initial_temperature_c = 0.0;
  sc.outer_kind = OuterBoundary::air;
  sc.outer_temperature_c = -15.0;
  sc.relative_humidity = 0.8;
  sc.duration_s = 3000;
  sc.output_interval_s = 100;
  validate_scenario(sc);
  FrontFixingSolver solver(sc);
  solver.advance_to(sc.duration_s);
  const Snapshot snap = solver.snapshot(true);
  EXPECT_LT(snap.inner_radius_m, 0.005);
  EXPECT_LT(snap.energy_balance_error, 1e-10);
  // The surface sits below the melting point and at most the wet-bulb depression below the air:
  // evaporation into air at 80 % takes h_m (rho_vs - rho_v) L_v <= h * 0.8 K here (h_m = h /
  // (rho c_p Le^(2/3)), rho_vs - rho_v = 0.2 * 1.6e-3 kg/m^3 at -15 C), so T_s > -15.8 C.
  const double ts = snap.profile.back().temperature_c;
  EXPECT_LT(ts, 0.0);
  EXPECT_GT(ts, -15.8);
}

}  // namespace
}  // namespace thaw::sim
