#pragma once
// Incompressible Boussinesq flow with heat on a MAC grid (mac_grid.h): planar 2D, axisymmetric
// (r, y) or 3D, gravity along -y. Finite volumes throughout: momentum in conservative form with
// central fluxes and the full viscous stress div(nu (grad u + grad u^T)) (nu varies with T; the
// axisymmetric hoop stress included), heat advected with Koren's limited kappa = 1/3 upwind
// face values (bounded) and diffused with central fluxes. Time: semi-implicit, first order:
// advection and buoyancy explicit (forward Euler), viscous diffusion, drag and heat conduction
// implicit (backward Euler, each a Helmholtz problem solved by multigrid-preconditioned CG).
// Two pressure solves behind PressureSolver (default: multigrid-preconditioned CG) per step:
// first the pressure p that balances the explicit forces R (R - grad p divergence-free, so a
// fluid in hydrostatic balance stays at rest), which the implicit step then carries (a pressure-
// correction scheme, Goda 1979; van Kan 1986), then the projection of the predicted velocity
// onto divergence-free fields (Chorin 1968). The implicit momentum step is written for the
// increment u* - u^n, so a steady state is the steady state of the spatial discretisation
// exactly, whatever the step. The step is limited by
// the advection only (Courant number, and dt <= 2 nu / |u|^2 for the central momentum
// fluxes), not by the viscous or conductive h^2 limits. A per-cell drag [1/s] (Carman-Kozeny in
// melting cells: Voller & Prakash 1987) is implicit, so a cell of infinite drag holds still: the
// ice of enthalpy-porosity.
// Walls are no-slip, each held at a temperature or adiabatic; the axisymmetric x_min is the axis.
// Results do not depend on the thread count (disjoint writes, sums in fixed order).
// Knows nothing of scenarios, files or the enthalpy solver.
#include <array>
#include <memory>
#include <vector>

#include "sim/flow/fluid_model.h"
#include "sim/flow/mac_grid.h"
#include "sim/flow/pressure_solver.h"

namespace thaw::sim::flow {

class MultigridPressureSolver;

struct WallCondition {
  enum class Kind { adiabatic, temperature };
  Kind kind = Kind::adiabatic;
  double temperature_c = 0;
};

/// Walls in the order x_min, x_max, y_min, y_max, z_min, z_max.
enum Wall { x_min = 0, x_max, y_min, y_max, z_min, z_max };

struct FlowProblem {
  MacGrid grid;
  FluidModel fluid;
  /// thermal diffusivity of the liquid [m^2/s]
  double thermal_diffusivity_m2_s = 0;
  std::array<WallCondition, 6> walls{};
  /// advective Courant number of a step (sum over axes of |u| dt / h)
  double courant = 0.5;
  /// pressure solve: largest net volume flow out of a cell after projection, relative to the
  /// largest face volume flow
  double pressure_tolerance = 1e-10;
  /// implicit viscous solves: largest residual relative to the right-hand side's largest entry
  /// (the increment's error; it vanishes with the right-hand side at steady state)
  double implicit_tolerance = 1e-8;
};

struct FlowStepReport {
  double dt_s = 0;
  /// pressure-solver iterations, both stages
  int pressure_iterations = 0;
  /// integral over the step of the heat entering through the walls, as
  /// alpha * integral dT/dn dA dt [K m^3 (planar: per m depth; axisymmetric: per radian)]
  double wall_heat_k_m3 = 0;
};

class FlowSolver {
 public:
  /// pressure: the back end (nullptr: MultigridPressureSolver). Starts at rest at 0 C.
  explicit FlowSolver(FlowProblem problem, std::unique_ptr<PressureSolver> pressure = nullptr);
  ~FlowSolver();

  const MacGrid& grid() const { return problem_.grid; }
  const FlowProblem& problem() const { return problem_; }
  /// cell temperatures [C], MacGrid::cell order
  std::vector<double>& temperature_c() { return temperature_; }
  const std::vector<double>& temperature_c() const { return temperature_; }
  /// face velocities of component d [m/s], MacGrid::face(d, ...) order (wall faces are 0)
  const std::vector<double>& velocity_m_s(int d) const { return velocity_[d]; }
  /// Replaces the face velocities of component d (a divergence-free field, walls 0), e.g. to carry
  /// a flow over when a coupled solver moves the box.
  void set_velocity_m_s(int d, std::vector<double> u);
  /// per-cell drag coefficient [1/s] (empty: none)
  void set_drag_per_s(std::vector<double> drag);
  /// true: step() advances the velocity only, the temperature held as set (a coupled solver
  /// carries the heat itself, with advective_transport below).
  void hold_temperature(bool hold) { hold_temperature_ = hold; }
  /// Net advective inflow of a cell quantity q into each cell by the current face velocities:
  /// out[c] = -sum over c's faces of A_f u_f q_f (outward), q_f Koren's limited upwind value;
  /// only faces between two cells with carries[c] != 0 carry anything, so the sum over the
  /// carrying cells is exactly zero [q m^3/s, per m depth | per radian | -].
  void advective_transport(const std::vector<double>& q, const std::vector<char>& carries,
                           std::vector<double>& out) const;

  /// The largest stable step [s]: the Courant number on the current velocity, the central
  /// momentum fluxes' forward-Euler limit dt <= 2 nu / sum_d u_d^2 per cell, and from rest a
  /// buoyancy limit (a fluid accelerated by b from rest moves b dt^2 <= courant h).
  double stable_time_step_s() const;
  FlowStepReport step(double dt_s);
  /// Helmholtz-solve iterations of the implicit viscous (all components) and conductive steps,
  /// summed over the steps so far.
  long implicit_iterations() const { return implicit_iterations_; }
  double time_s() const { return time_s_; }

  /// integral of T over the fluid [K m^3, per m depth | per radian | -]
  double thermal_content_k_m3() const;
  /// alpha * integral of dT/dn over wall w (heat flow in, over rho c) [K m^3/s, same units]
  double wall_heat_flow_k_m3_s(int wall) const;
  /// largest |div u| over the cells [1/s]
  double max_divergence_per_s() const;
  /// largest speed at a cell centre [m/s]
  double max_speed_m_s() const;
  /// velocity component d interpolated to the centre of cell (i, j, k) [m/s]
  double cell_velocity_m_s(int d, int i, int j, int k) const;

 private:
  using Field = std::array<std::vector<double>, 3>;
  void momentum_rhs(const Field& u, const std::vector<double>& t, Field& out) const;
  /// dT/dt of cells by advection with u and/or diffusion (walls included) [K/s].
  void temperature_rhs(const Field& u, const std::vector<double>& t, bool advect, bool diffuse,
                       std::vector<double>& out) const;
  std::array<double, 6> wall_heat_flows(const std::vector<double>& t) const;
  /// Projects u onto divergence-free velocities: u -= a grad psi, div(a grad psi) = div u,
  /// a = 1 / (1 + dt D) per face; returns the solve's iterations.
  int project(Field& u, std::vector<double>& psi);
  /// nu and buoyancy per cell from t; true if nu changed.
  bool update_cell_properties(const std::vector<double>& t);
  /// The implicit momentum predictor: u <- u + delta, (V (1 + dt D) - dt V nu L) delta =
  /// dt V (R - grad p - D u), L the component-wise Laplacian (with the hoop term).
  int momentum_predictor(double dt, bool nu_changed);
  /// The implicit conduction of t over dt after its explicit advection; returns the iterations
  /// and adds the wall heat to report.
  int conduct(double dt, FlowStepReport& report);
  /// The step of an operator's last full multigrid build and the updates of its finest level
  /// since (-1: never built).
  struct OperatorBuild {
    double dt = 0;
    int updates = -1;
  };
  /// true: rebuild all levels (and note it); false: update the finest level only.
  static bool rebuild_coarse(OperatorBuild& build, double dt);
  /// (Re)builds the pressure operator for the implicit drag over drag_dt (0: no drag).
  void set_pressure_operator(double drag_dt);

  FlowProblem problem_;
  std::unique_ptr<PressureSolver> pressure_;
  Field velocity_;
  std::vector<double> temperature_;
  std::vector<double> drag_;
  // per cell, refreshed from the temperature of each stage: nu [m^2/s], buoyancy [m/s^2]
  std::vector<double> nu_, buoyancy_;
  std::vector<double> psi_;     // the last projection's potential (warm start)
  std::vector<double> p_;       // kinematic pressure p [m^2/s^2] balancing the explicit forces
  Field rhs_, forces_, delta_;  // R(u^n); a R; the predictor's increment (warm start)
  std::vector<double> t_rhs_, t_delta_;
  // the implicit steps' Helmholtz solvers (one per velocity component, one for heat) and the
  // step and properties they were built for
  std::array<std::unique_ptr<MultigridPressureSolver>, 3> viscous_;
  std::unique_ptr<MultigridPressureSolver> conduction_;
  double viscous_dt_ = -1, conduction_dt_ = -1;
  OperatorBuild pressure_built_, viscous_built_;
  bool viscous_drag_changed_ = true;
  long implicit_iterations_ = 0;
  // per face: 1 / (1 + dt D) of the current stage (empty without drag)
  std::array<std::vector<double>, 3> face_factor_;
  double operator_drag_dt_ = 0;
  bool drag_changed_ = false;
  bool hold_temperature_ = false;
  // loops run in parallel only on grids large enough to pay for a barrier
  bool parallel_ = false;
  double time_s_ = 0;
};

}  // namespace thaw::sim::flow
