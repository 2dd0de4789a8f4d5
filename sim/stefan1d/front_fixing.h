#pragma once
// The radial two-phase Stefan solver: a liquid core 0 <= r < s(t) inside an ice shell
// s(t) < r < b(t), planar / cylindrical / spherical, on a front-fitted moving grid.
//
// Method (see docs/simulate.md for the derivation):
//  * Landau transform: each phase is mapped onto [0, 1] between its moving ends and split into
//    equal cells that stretch with it; the water|ice front and the ablating surface are grid
//    faces, so the front is never smeared or stair-stepped.
//  * Conservative finite volumes in ALE form: each cell's enthalpy changes by the conducted heat
//    through its faces plus the enthalpy swept by its moving faces, with swept volumes computed
//    exactly from the face positions (geometric conservation). One-sided second-order gradients
//    at Dirichlet faces (front, held walls). The discrete total enthalpy then changes exactly by
//    the discrete boundary heat (+ drained melt), to Newton tolerance.
//  * TR-BDF2 in time (Bank et al. 1985; Hosea & Shampine 1996): second order and L-stable, so
//    the discontinuous initial data of a warm core in a cold shell does not ring.
//  * Newton (finite-difference Jacobian, refreshed every few iterations) on the front positions
//    with the temperatures eliminated: each phase's temperatures are one tridiagonal solve for
//    given front positions, so this is Newton on the Schur complement of the coupled system.
//  * Adaptive steps by step doubling on front positions and temperatures; steps are clipped to
//    land exactly on requested output times; events are located to tolerance.
// Knows nothing of files, TOML or the command line.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sim/scenario/scenario.h"

namespace thaw::sim {

/// A time-stamped change of regime: "melt_onset", "core_frozen", "break_through", and the
/// rarer "ablation_stop" (net heat at the ablating surface turned negative) and "fully_melted"
/// (a block without liquid ablated away).
struct Event {
  std::string kind;
  double time_s = 0;    ///< when it happened [s]
  double radius_m = 0;  ///< where: the ablating surface, the frozen centre, the meeting fronts [m]
};

/// One point of a temperature profile (cell centres plus the phase boundaries).
struct ProfilePoint {
  double r_m = 0;            ///< position [m]
  double temperature_c = 0;  ///< [C]
  const char* phase = "";    ///< "water" | "ice"
};

/// The solver's state at one instant, in the units of interfaces.csv.
struct Snapshot {
  double time_s = 0;
  double inner_radius_m = 0;    ///< s: water|ice front (0 without liquid) [m]
  double outer_radius_m = 0;    ///< b: ice surface [m] (== s once the ice is gone)
  double liquid_volume_m3 = 0;  ///< per m^2 (planar), per m (cylinder), total (sphere)
  double ice_volume_m3 = 0;
  /// |H(t) - H(0) - heat in + drained melt + removed remnants| / reference energy, cumulative.
  double energy_balance_error = 0;
  double enthalpy_j = 0;  ///< discrete total enthalpy relative to ice at T_m [J (per m^2, per m)]
  double heat_in_j = 0;   ///< heat entered through the boundaries since t = 0
  double drained_j = 0;   ///< enthalpy carried away by drained melt since t = 0
  bool ablating = false;  ///< outer surface held at T_m and receding
  std::vector<ProfilePoint> profile;
};

struct SolverStatistics {
  long steps = 0;           ///< accepted steps
  long rejected_steps = 0;  ///< rejected by the error test, Newton failure or event location
  long newton_iterations = 0;
  long linear_solves = 0;            ///< tridiagonal solves (one per phase per residual evaluation)
  double max_step_energy_error = 0;  ///< max over steps of |dH - heat| / reference energy
  double removed_energy_j = 0;       ///< enthalpy of vanishing remnants removed (booked, tiny)
  double start_energy_j = 0;  ///< heat of the analytic small-time start (zero-thickness phase)
  double start_time_s = 0;    ///< t0 of the analytic small-time start (0 if none)
  double min_step_s = 0, max_step_s = 0;
};

/// Options for validation studies; the defaults are what thaw simulate uses.
struct SolverOptions {
  /// > 0: constant steps of this size [s] (clipped at output times), no error control; for
  /// measuring the order in time. 0: adaptive steps under scenario.time_tolerance.
  double fixed_step_s = 0;
  /// Start at t = start_time_s from this temperature profile T(r) [C] (cell averages are
  /// taken by Gauss quadrature) instead of the scenario's uniform temperatures; the fronts are
  /// at scenario.inner_radius_m / outer_radius_m. Used to start from an exact solution.
  std::function<double(double)> initial_temperature_c;
  double start_time_s = 0;
};

class FrontFixingSolver {
 public:
  /// `scenario` must be valid (validate_scenario); THAW_CHECK otherwise.
  explicit FrontFixingSolver(const Scenario& scenario, SolverOptions options = {});
  ~FrontFixingSolver();
  FrontFixingSolver(const FrontFixingSolver&) = delete;
  FrontFixingSolver& operator=(const FrontFixingSolver&) = delete;

  /// Advances to exactly t_target [s] (> time()), or until no ice is left. Returns the time
  /// reached (t_target unless the run ended earlier).
  double advance_to(double t_target);
  double time() const;
  /// True once no ice is left (break-through or fully ablated): nothing more to simulate.
  bool finished() const;
  Snapshot snapshot(bool with_profile) const;
  /// The state at t = 0 exactly as the scenario gives it, with uniform temperatures: differs
  /// from the first snapshot() only when a phase of zero thickness was started analytically at
  /// statistics().start_time_s > 0.
  Snapshot initial_snapshot(bool with_profile) const;
  const std::vector<Event>& events() const;
  const SolverStatistics& statistics() const;
  /// Energy scale of the relative balance error: latent heat of the whole initial volume [J].
  double reference_energy() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace thaw::sim
