#include "sim/format/simulation_output.h"

#include <cmath>

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "base/atomic_file.h"
#include "base/check.h"
#include "base/error.h"
#include "sim/format/grid_field_file.h"
#include "sim/format/interface_history.h"
#include "sim/format/scenario_file.h"

namespace thaw::sim {
namespace fs = std::filesystem;

namespace {

/// The largest energy balance error over the run's output steps (summary.json "solver").
double max_energy_balance_error(const SimulationResult& r) {
  double max_error = 0;
  for (const Snapshot& snap : r.snapshots)
    max_error = std::max(max_error, snap.energy_balance_error);
  return max_error;
}

/// summary.json "final": the last output step's radii and volumes.
nlohmann::json final_state_json(const SimulationResult& r) {
  const Snapshot& last = r.snapshots.back();
  return {{"inner_radius_m", last.inner_radius_m},
          {"outer_radius_m", last.outer_radius_m},
          {"liquid_volume_m3", last.liquid_volume_m3},
          {"ice_volume_m3", last.ice_volume_m3}};
}

std::filesystem::path field_file(const std::filesystem::path& dir, std::size_t step) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "step_%06zu.grid", step);
  return dir / "fields" / buf;
}

nlohmann::json grid_summary_json(const SimulationResult& r) {
  nlohmann::json j;
  j["parameters"] = scenario_to_json(r.scenario);
  j["events"] = nlohmann::json::array();
  for (std::size_t i = 0; i < r.grid_events.size(); ++i) {
    const GridEvent& e = r.grid_events[i];
    j["events"].push_back({{"kind", e.kind},
                           {"time_s", e.time_s},
                           {"radius_m", r.events[i].radius_m},
                           {"position_m", e.position_m}});
  }
  j["wall_time_s"] = r.wall_time_s;
  if (!r.flow_records.empty()) {
    nlohmann::json rows = nlohmann::json::array();
    for (const auto& f : r.flow_records)
      rows.push_back({{"time_s", f[0]}, {"max_speed_m_s", f[1]}, {"rayleigh", f[2]}});
    j["flow"] = rows;
  }
  // The water's books per output (material volumes: the solver has one density for ice and
  // water; docs/simulate.md, "Water held in an open shell"); level null while no cup holds
  // water.
  nlohmann::json water = nlohmann::json::array();
  for (const auto& w : r.water_records)
    water.push_back({{"time_s", w.time_s},
                     {"held_m3", w.held_m3},
                     {"level_m", std::isfinite(w.level_m) ? nlohmann::json(w.level_m) : nullptr},
                     {"enclosed_m3", w.enclosed_m3},
                     {"liquid_m3", w.liquid_m3},
                     {"ice_m3", w.ice_m3},
                     {"drained_m3", w.drained_m3}});
  j["water"] = water;
  const GridStatistics& s = r.grid_statistics;
  const GridField& f = r.grid;
  j["solver"] = {
      {"method", "fixed-grid enthalpy (Voller & Prakash), backward Euler, semismooth Newton + CG"},
      {"grid",
       {{"geometry", to_string(f.geometry)},
        {"cells", f.cells},
        {"origin_m", f.origin_m},
        {"spacing_m", f.spacing_m}}},
      {"steps", s.steps},
      {"rejected_steps", s.rejected_steps},
      {"newton_iterations", s.newton_iterations},
      {"cg_iterations", s.cg_iterations},
      {"cell_updates", s.cell_updates},
      {"loose_steps", s.loose_steps},
      {"stagnant_steps", s.stagnant_steps},
      {"unconverged_steps", s.unconverged_steps},
      {"removed_ice_m3", s.removed_ice_m3},
      {"min_step_s", s.min_step_s},
      {"max_step_s", s.max_step_s},
      {"max_step_energy_error", s.max_step_energy_error},
      {"max_energy_balance_error", max_energy_balance_error(r)},
      {"reference_energy_j", r.reference_energy_j}};
  j["output"] = {
      {"rows", r.snapshots.size()},
      {"ended_early", r.ended_early},
      {"final_time_s", r.snapshots.back().time_s},
      {"radii", "volume-equivalent: inner from the liquid volume, outer from ice + liquid"}};
  j["final"] = final_state_json(r);
  return j;
}

void write_grid_outputs(const std::filesystem::path& dir, const SimulationResult& r) {
  write_interfaces_csv(dir / "interfaces.csv", r.interface_records());
  write_file_atomic(dir / "boundary_heat.csv", format_boundary_heat_csv(r));
  ensure_directory(dir / "fields");
  // Fields kept in memory are written here; streamed ones (field_stream) are there already.
  for (std::size_t i = 0; i < r.fields.size(); ++i)
    write_grid_field(field_file(dir, i), r.fields[i]);
  write_file_atomic(dir / "summary.json", summary_json_text(r));
}

}  // namespace

FieldSink field_stream(const std::filesystem::path& dir, const Scenario& scenario,
                       std::size_t outputs) {
  return [dir, scenario, outputs](std::size_t step, const GridField& field) {
    if (step == 0) {
      // Before the first step is solved: every output's file, against the free space.
      ensure_directory(dir / "fields");
      const double need = static_cast<double>(outputs) * (96.0 + field_bytes(field, 1));
      std::error_code ec;
      const auto space = std::filesystem::space(dir, ec);
      if (!ec && need > static_cast<double>(space.available)) {
        const auto gb = [](double bytes) {
          char buf[32];
          std::snprintf(buf, sizeof buf, "%.3g GB", bytes / 1e9);
          return std::string(buf);
        };
        char head[96];
        std::snprintf(head, sizeof head, "(%.6g s) asks for %zu field files of %.3g MB, ",
                      scenario.output_interval_s, outputs, (96.0 + field_bytes(field, 1)) / 1e6);
        const fs::path where = dir.has_parent_path() ? dir.parent_path() : fs::path(".");
        throw UserError("", "simulation.output_interval_s",
                        head + gb(need) + " in all, more than the " +
                            gb(static_cast<double>(space.available)) + " free on the disk of " +
                            where.string() + "; use a larger output_interval_s");
      }
    }
    write_grid_field(field_file(dir, step), field);
  };
}

std::string summary_json_text(const SimulationResult& r) {
  THAW_CHECK(!r.snapshots.empty(), "a simulation result has at least one snapshot");
  if (r.scenario.grid != GridGeometry::none) return grid_summary_json(r).dump(2) + "\n";
  nlohmann::json j;
  j["parameters"] = scenario_to_json(r.scenario);
  j["events"] = nlohmann::json::array();
  for (const Event& e : r.events)
    j["events"].push_back({{"kind", e.kind}, {"time_s", e.time_s}, {"radius_m", e.radius_m}});
  j["wall_time_s"] = r.wall_time_s;
  const SolverStatistics& s = r.statistics;
  j["solver"] = {
      {"method", "front-fixing finite volumes (Landau transform, ALE), TR-BDF2, step doubling"},
      {"steps", s.steps},
      {"rejected_steps", s.rejected_steps},
      {"newton_iterations", s.newton_iterations},
      {"linear_solves", s.linear_solves},
      {"min_step_s", s.min_step_s},
      {"max_step_s", s.max_step_s},
      {"max_step_energy_error", s.max_step_energy_error},
      {"max_energy_balance_error", max_energy_balance_error(r)},
      {"reference_energy_j", r.reference_energy_j},
      {"removed_remnant_energy_j", s.removed_energy_j},
      {"small_time_start_s", s.start_time_s},
      {"small_time_start_energy_j", s.start_energy_j}};
  j["output"] = {{"rows", r.snapshots.size()},
                 {"ended_early", r.ended_early},
                 {"final_time_s", r.snapshots.back().time_s}};
  j["final"] = final_state_json(r);
  return j.dump(2) + "\n";
}

void write_simulation_outputs(const std::filesystem::path& dir, const SimulationResult& r) {
  THAW_CHECK(!r.snapshots.empty(), "a simulation result has at least one snapshot");
  if (r.scenario.grid != GridGeometry::none) return write_grid_outputs(dir, r);
  write_interfaces_csv(dir / "interfaces.csv", r.interface_records());
  const auto profiles = dir / "profiles";
  ensure_directory(profiles);
  char buf[128];
  for (std::size_t i = 0; i < r.snapshots.size(); ++i) {
    std::string text = "r_m,temperature_c,phase\n";
    for (const ProfilePoint& p : r.snapshots[i].profile) {
      std::snprintf(buf, sizeof buf, "%.17g,%.17g,%s\n", p.r_m, p.temperature_c, p.phase);
      text += buf;
    }
    std::snprintf(buf, sizeof buf, "step_%06zu.csv", i);
    write_file_atomic(profiles / buf, text);
  }
  write_file_atomic(dir / "summary.json", summary_json_text(r));
}

std::string format_boundary_heat_csv(const SimulationResult& r) {
  THAW_CHECK(r.boundary_heat_j.size() == r.snapshots.size(),
             "a grid result books the boundary heat of every snapshot");
  std::string text = "time_s,face,heat_flow_w\n";
  for (std::size_t k = 1; k < r.snapshots.size(); ++k) {
    const double t = r.snapshots[k].time_s, interval = t - r.snapshots[k - 1].time_s;
    for (std::size_t f = 0; f < r.boundary_faces.size(); ++f) {
      const double q = (r.boundary_heat_j[k][f] - r.boundary_heat_j[k - 1][f]) / interval;
      char buf[96];
      std::snprintf(buf, sizeof buf, ",%.17g\n", q);
      char time[40];
      std::snprintf(time, sizeof time, "%.17g,", t);
      text += time + r.boundary_faces[f] + buf;
    }
  }
  return text;
}

std::optional<std::string> foreign_entry(const std::filesystem::path& dir) {
  static const char* const kOwn[] = {"interfaces.csv", "summary.json", "profiles",         "fields",
                                     "mesh",           "mesh.partial", "boundary_heat.csv"};
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return std::nullopt;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    bool own = name.find(".tmp-") != std::string::npos;
    for (const char* n : kOwn) own = own || name == n;
    if (!own) return name;
  }
  return std::nullopt;
}

}  // namespace thaw::sim
