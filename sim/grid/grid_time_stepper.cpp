#include "sim/grid/grid_time_stepper.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <omp.h>

#include "base/check.h"

namespace thaw::sim {

namespace {

/// Newton failing at this step accepts its last iterate (energy is conserved by the final
/// update whatever the iterate) and counts it in GridStatistics::unconverged_steps.
constexpr double kMinStep_s = 1e-3;
/// The ice is gone (fully_melted, the run ends) below this fraction of the initial material
/// volume: stray sub-cell remnants would otherwise linger for minutes at a few mm^3.
constexpr double kGoneFraction = 1e-5;
/// Runaway guard (as the 1D solver's): after every window of kGuardWindowCellSteps of work
/// (attempted steps x cells; a cell step costs about 0.3 us on one core of the 2-core CI
/// machine with its Newton and CG iterations: the hollow cube's 230 steps x 140000 cells took
/// 10.5 s of CPU), the work still needed at the window's pace is projected; beyond
/// kGuardMaxCellSteps (about 8 hours of CPU there, 12000 steps of the largest grid the rules
/// accept, against the few hundred of a shipped scenario) the step has collapsed and the run
/// would never end in practice. Work, not the clock: the same run stops at the same step.
constexpr double kGuardWindowCellSteps = 1e7;
constexpr double kGuardMaxCellSteps = 1e11;
/// A window whose mean step is at least this fraction of max_step_s was paced by the cap.
constexpr double kAtCapFraction = 0.5;

std::string seconds_text(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g s", t);
  return buf;
}

}  // namespace

GridTimeStepper::GridTimeStepper(const GridProblem& problem, const GridMesh& mesh,
                                 const PhaseRelation& phase, CellState& cells, CavityDrain& cavity,
                                 SurfaceArea& surface, ConductionOperator& op, NewtonSolver& newton,
                                 GridFlow* flow)
    : p(problem),
      m_mesh(mesh),
      m_phase(phase),
      m_cells(cells),
      m_cavity(cavity),
      m_surface(surface),
      m_op(op),
      m_newton(newton),
      m_flow(flow) {
  m_block_sums.assign(static_cast<std::size_t>(mesh.block_count()), BlockSums{});
  THAW_CHECK(
      problem.face_of_cell.empty() || static_cast<long>(problem.face_of_cell.size()) == mesh.n,
      "a grid problem gives each cell's face or none");
  m_face_heat_in.assign(body_face_names(problem.face_shape).size(), 0.0);
  const std::vector<double>& m = cells.m;
  initial_material = sum_cells(mesh.n, [&](long c) { return m[c] * mesh.vol[c]; });
  m_most_ice = sum_cells(
      mesh.n, [&](long c) { return m[c] * (1 - phase.liquid(cells.H[c])) * mesh.vol[c]; });
  m_reference = phase.latent * initial_material;
  THAW_CHECK(m_reference > 0, "a grid problem needs some material");
  // The initial state drains nothing by definition: only classify which liquid is enclosed.
  TeamShared alone;  // the constructor's phases on this thread only
  BlockTeam team(alone, 0, mesh.block_count());
  cavity.classify(team);
  had_enclosed_liquid = cavity.enclosed_liquid_volume() > 0;
  surface.update(team);
  m_e0 = energy();
  dt_next = p.fixed_step_s > 0 ? p.fixed_step_s : std::min(p.max_step_s, 0.05);
}

double GridTimeStepper::energy() const {
  const std::vector<double>& m = m_cells.m;
  const std::vector<double>& H = m_cells.H;
  return sum_cells(m_mesh.n, [&](long c) { return m[c] * m_mesh.vol[c] * H[c]; });
}

/// One step of size dt from the current state, run by the team's leader: coefficients, Newton,
/// the conservative final update, draining, events; false (state restored) if Newton failed and
/// the step can still shrink.
///
/// The step's bookkeeping is fused into as few phases as possible (each phase ends with a
/// barrier, and on a shared machine each barrier can wait a time slice for a descheduled
/// thread): start (energy, coefficients), Newton, final update (with the openness the flood
/// fill needs), one serial part (flood fill, break-through), drain (with exposure, energies and
/// the end events' sums), one serial part (books, melt onset, the re-flood), and only when
/// something drained the exposure and surface-area phases; then the serial end of the step.
GridTimeStepper::StepResult GridTimeStepper::step(BlockTeam& team,
                                                  const std::function<bool()>& stop) {
  std::vector<double>& m = m_cells.m;
  std::vector<double>& H = m_cells.H;
  std::vector<double>& H_start = m_cells.H_start;
  const std::vector<double>& T = m_cells.T;
  std::vector<double>& T_start = m_cells.T_start;
  std::vector<double>& f_start = m_cells.f_start;
  std::vector<double>& rate = m_cells.rate;
  const std::vector<double>& vol = m_mesh.vol;
  const PhaseRelation& ph = m_phase;
  m_surface.prepare_step(team, dt);
  // assemble reads the neighbours' H, which nothing writes in this phase
  team.for_blocks([&](long bl) {
    double e = 0;
    m_mesh.for_cells(bl, [&](long c, int i, int j, int k) {
      T_start[c] = m[c] > 0 ? ph.temperature(H[c]) : 0.0;
      f_start[c] = ph.liquid(H[c]);
      e += m[c] * vol[c] * H[c];
      H_start[c] = H[c];
      m_op.assemble(c, i, j, k);
    });
    m_block_sums[static_cast<std::size_t>(bl)].energy_start = e;
  });
  const double e_before = sum_blocks([](const BlockSums& b) { return b.energy_start; });
  const GridStatistics stats_before = m_stats;
  const NewtonOutcome outcome = m_newton.solve(team, dt, m_stats, stop);
  const bool ok = outcome != NewtonOutcome::unconverged && outcome != NewtonOutcome::stopped;
  if (outcome == NewtonOutcome::stopped || (!ok && dt > kMinStep_s)) {
    team.for_blocks([&](long bl) {
      for (long c = bl * kBlock; c < m_mesh.block_end(bl); ++c) H[c] = H_start[c];
    });
    if (outcome != NewtonOutcome::stopped) return StepResult::rejected;
    m_stats = stats_before;  // as if the step had never started
    return StepResult::stopped;
  }
  if (!ok && team.leader()) ++m_stats.unconverged_steps;
  // Conservative final update: each cell's enthalpy from its balance at the final
  // temperatures (T is current: Newton's last iteration set it from H), so that the interior
  // fluxes cancel exactly in the total. heat_rate reads the temperatures only, so each cell
  // may overwrite its own H. Then the cell's openness for the flood fill.
  team.for_blocks([&](long bl) {
    double heat = 0;
    auto& face_heat = m_block_sums[static_cast<std::size_t>(bl)].face_heat;
    face_heat.fill(0.0);
    m_mesh.for_cells(bl, [&](long c, int i, int j, int k) {
      if (m[c] > 0) {
        H[c] = H_start[c] + dt * m_op.heat_rate(c, i, j, k) / (m[c] * vol[c]);
        const double q = m_op.boundary_heat(c, T[c]);
        heat += q;
        if (q != 0) {
          const FaceWeights by_face = m_op.boundary_heat_by_face(c, i, j, k, T[c]);
          for (std::size_t f = 0; f < kMaxBodyFaces; ++f) face_heat[f] += by_face[f];
        }
      }
      m_cavity.mark_open(c);
    });
    m_block_sums[static_cast<std::size_t>(bl)].heat = heat;
  });
  const double heat_step = dt * sum_blocks([](const BlockSums& b) { return b.heat; });
  team.serial([&] {
    m_time = dt == step_remaining ? step_target : m_time + dt;
    m_heat_in += heat_step;
    for (std::size_t f = 0; f < m_face_heat_in.size(); ++f)
      m_face_heat_in[f] += dt * sum_blocks([f](const BlockSums& b) { return b.face_heat[f]; });
    m_cavity.fill_outside();
    record_openings();
  });
  // exposure, draining (booked), openness for a re-flood, energies and the end events' sums
  team.for_blocks([&](long bl) {
    BlockSums& b = m_block_sums[static_cast<std::size_t>(bl)];
    b.drain = DrainTally{};
    b.enclosed = EnclosedTally{};
    b.energy_end = b.drained_m3 = b.ice = b.dtemp = b.dmelt = 0;
    m_mesh.for_cells(bl, [&](long c, int i, int j, int k) {
      m_cavity.exposure(c, i, j, k);
      const double before = m[c];
      m_cavity.drain_cell(c, b.drain);
      b.drained_m3 += (before - m[c]) * vol[c];
      m_cavity.mark_open(c);
      b.energy_end += m[c] * vol[c] * H[c];
      m_cavity.add_enclosed(c, b.enclosed);
      b.ice += m_cavity.ice_fraction(c) * vol[c];
      rate[c] = m[c] > 0 ? (ph.temperature(H[c]) - T_start[c]) / dt : 0.0;
      if (m[c] > 0) {
        b.dtemp = std::max(b.dtemp, std::abs(ph.temperature(H[c]) - T_start[c]));
        b.dmelt = std::max(b.dmelt, std::abs(ph.liquid(H[c]) - f_start[c]));
      }
    });
  });
  const double drained_step = sum_blocks([](const BlockSums& b) { return b.drain.drained; });
  team.serial([&] {
    const double drained_before = m_drained;
    m_drained += drained_step;
    m_drained_m3 += sum_blocks([](const BlockSums& b) { return b.drained_m3; });
    m_stats.removed_ice_m3 += sum_blocks([](const BlockSums& b) { return b.drain.removed; });
    double most = 0;
    long most_cell = -1;
    for (const BlockSums& b : m_block_sums)
      if (b.drain.most_drained_cell >= 0 && b.drain.most_drained > most) {
        most = b.drain.most_drained;
        most_cell = b.drain.most_drained_cell;
      }
    if (!melt_started && most_cell >= 0) {
      melt_started = true;
      m_events.push_back({"melt_onset", m_time, m_mesh.centre(most_cell)});
    }
    const double e_end = sum_blocks([](const BlockSums& b) { return b.energy_end; });
    const double err =
        std::abs(e_end - e_before - heat_step + (m_drained - drained_before)) / m_reference;
    m_stats.max_step_energy_error = std::max(m_stats.max_step_energy_error, err);
    m_stats.steps++;
    m_stats.min_step_s = m_stats.steps == 1 ? dt : std::min(m_stats.min_step_s, dt);
    m_stats.max_step_s = std::max(m_stats.max_step_s, dt);
    if (drained_step > 0) {  // the drained cells opened: the next outside
      m_cavity.fill_outside();
      record_openings();
    }
    m_surface.after_step(drained_step > 0,
                         sum_blocks([](const BlockSums& b) { return b.drained_m3; }), dt);
  });
  if (drained_step > 0) {
    // exposure as the next step sees it (its surface areas follow at its start)
    team.for_blocks([&](long bl) {
      BlockSums& b = m_block_sums[static_cast<std::size_t>(bl)];
      b.enclosed = EnclosedTally{};
      m_mesh.for_cells(bl, [&](long c, int i, int j, int k) {
        m_cavity.exposure(c, i, j, k);
        m_cavity.add_enclosed(c, b.enclosed);
      });
    });
  }
  // The water's flow over the accepted step, with the buoyancy and drag of the state it ended
  // in; its velocities carry the water's heat in the next step (explicit there: a fixed rate
  // per cell). A rejected or stopped step leaves the flow as it was, so a stopped run continues
  // bit for bit.
  if (m_flow)
    team.serial([&] {
      m_flow->advance(dt);
      m_stats.flow_steps = m_flow->flow_steps();
      m_stats.flow_cell_steps = m_flow->flow_cell_steps();
    });
  return StepResult::accepted;
}

/// The cavities' openings found by the last flood fill as events (serial).
void GridTimeStepper::record_openings() {
  if (const auto opened = m_cavity.detect_break_through())
    m_events.push_back({"break_through", m_time, *opened});
  for (const auto& [where, level] : m_cavity.take_level_drops())
    m_events.push_back({"water_level_drop", m_time, where});
}

/// The serial end of an accepted step: core_frozen (at the last enclosed liquid's cell),
/// fully_melted, and the next step size.
void GridTimeStepper::end_of_step(double step_dt, double saved) {
  const double enclosed = sum_blocks([](const BlockSums& b) { return b.enclosed.enclosed; });
  const double ice = sum_blocks([](const BlockSums& b) { return b.ice; });
  // the body the air sees follows its volume (ice and enclosed water)
  bool air = p.surface_kind == OuterBoundary::air;
  for (const SurfaceCondition& f : p.face_conditions) air = air || f.kind == OuterBoundary::air;
  if (air && ice + enclosed > 0)
    m_op.set_air_diameter(std::cbrt(6 * (ice + enclosed) / std::numbers::pi));
  if (had_enclosed_liquid && !m_cavity.broke_through() && !core_frozen && enclosed == 0) {
    core_frozen = true;
    m_events.push_back({"core_frozen", m_time, m_mesh.centre(last_liquid_cell)});
  }
  if (enclosed > 0) {  // the lowest-index cell with the most enclosed liquid
    double most = -1;
    for (const BlockSums& b : m_block_sums)
      if (b.enclosed.wettest_cell >= 0 && b.enclosed.wettest > most) {
        most = b.enclosed.wettest;
        last_liquid_cell = b.enclosed.wettest_cell;
      }
  }
  // A body that starts as water ([shape] fill = "water") has no ice to lose until some forms.
  m_most_ice = std::max(m_most_ice, ice);
  if (ice <= kGoneFraction * initial_material && m_most_ice > kGoneFraction * initial_material) {
    m_done = true;
    long last = m_mesh.n - 1;
    while (last > 0 && m_cells.m[last] == 0) --last;
    m_events.push_back({"fully_melted", m_time, m_mesh.centre(last)});
  }
  if (p.fixed_step_s > 0) {
    dt_next = p.fixed_step_s;
    return;
  }
  const double flow_limit = m_flow ? m_flow->max_step_s() : p.max_step_s;
  const double dtemp_max = max_blocks([](const BlockSums& b) { return b.dtemp; });
  const double dmelt_max = max_blocks([](const BlockSums& b) { return b.dmelt; });
  double factor = 2.0;
  if (dtemp_max > 0) factor = std::min(factor, 0.9 * p.step_temperature_change_k / dtemp_max);
  if (dmelt_max > 0) factor = std::min(factor, 0.9 * p.step_melt_fraction / dmelt_max);
  factor = std::max(0.3, factor);
  // a step shortened to land on the target keeps the previous size unless it must shrink
  dt_next = step_dt < saved ? std::min(saved, step_dt * factor)
                            : std::min(p.max_step_s, step_dt * factor);
  if (step_dt < saved && factor >= 1) dt_next = saved;
  dt_next = std::min(dt_next, flow_limit);
}

/// The steps to target in one OpenMP parallel region: the leader runs them, the other
/// threads help with each phase's blocks and sleep while the leader does the serial
/// bookkeeping (events, the flood fill), instead of spinning in OpenMP's barriers.
double GridTimeStepper::advance_to(double target, const std::function<bool()>& stop) {
  TeamShared shared;
  m_runaway.clear();
#pragma omp parallel if (m_mesh.n > kParallelCells)
  {
    BlockTeam team(shared, omp_get_thread_num(), m_mesh.block_count());
    if (team.leader()) {
      advance_team(team, target, stop);
      team.finish();
    } else {
      team.serve();
    }
  }
  if (!m_runaway.empty())
    throw GridRunaway(m_runaway, m_last_window_step_s >= kAtCapFraction * p.max_step_s);
  return m_time;
}

std::string GridTimeStepper::runaway(double target) {
  ++m_attempts;
  if (p.fixed_step_s > 0) return {};
  const double n = static_cast<double>(m_mesh.n);
  const double cost = static_cast<double>(m_attempts) * n;
  if (cost - m_guard_cost < kGuardWindowCellSteps) return {};
  const double attempts = (cost - m_guard_cost) / n;
  const double pace_s = (m_time - m_guard_time_s) / (cost - m_guard_cost);  // per cell step
  m_last_window_step_s = (m_time - m_guard_time_s) / attempts;
  const double remaining_s = std::max(p.end_time_s, target) - m_time;
  m_guard_cost = cost;
  m_guard_time_s = m_time;
  if (pace_s * kGuardMaxCellSteps >= remaining_s) return {};
  char needed[64] = "no progress in the last steps";
  if (m_last_window_step_s > 0)
    std::snprintf(needed, sizeof needed, "%.3g more steps of %ld cells would be needed",
                  remaining_s / m_last_window_step_s, m_mesh.n);
  return "its steps average " + seconds_text(m_last_window_step_s) +
         " at t = " + seconds_text(m_time) + " (" + std::to_string(m_stats.steps) +
         " steps so far); " + needed + ": the run would not end";
}

/// Run by the team's leader; the helpers only run the blocks of the phases it posts (posting
/// a phase publishes everything the leader wrote before).
void GridTimeStepper::advance_team(BlockTeam& team, double target,
                                   const std::function<bool()>& stop) {
  while (!m_done && m_time < target) {
    if (stop && stop()) return;
    m_runaway = runaway(target);
    if (!m_runaway.empty()) return;
    const double remaining = target - m_time;
    double step_dt = std::min(dt_next, remaining);
    // avoid a sliver step before the target
    if (remaining - step_dt < 1e-3 * step_dt) step_dt = remaining;
    const double saved = dt_next;
    if (team.leader()) {
      dt = step_dt;
      step_remaining = remaining;
      step_target = target;
    }
    const StepResult result = step(team, stop);
    if (result == StepResult::stopped) {
      --m_attempts;  // as if never attempted: the guard's windows do not see the stop
      return;
    }
    if (result == StepResult::rejected) {
      team.serial([&] {
        ++m_stats.rejected_steps;
        dt_next = std::max(0.5 * step_dt, 0.99 * kMinStep_s);
      });
      continue;
    }
    team.serial([&] { end_of_step(step_dt, saved); });
  }
}

}  // namespace thaw::sim
