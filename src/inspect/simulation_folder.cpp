#include "src/inspect/simulation_folder.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "base/error.h"
#include "base/format/mesh_manifest.h"
#include "sim/format/interface_history.h"

namespace thaw::inspect {
namespace fs = std::filesystem;

bool is_simulation_folder(const fs::path& path) {
  std::error_code ec;
  return fs::is_directory(path, ec) && fs::is_regular_file(path / "interfaces.csv", ec);
}

std::vector<MeshedStep> read_mesh_manifest(const fs::path& manifest,
                                           const std::vector<sim::InterfaceRecord>& rows) {
  const std::string name = manifest.string();
  const meshio::MeshManifestFile file = meshio::read_mesh_manifest(manifest);
  const fs::path base = manifest.parent_path();
  std::vector<MeshedStep> steps;
  for (std::size_t k = 0; k < file.steps.size(); ++k) {
    const meshio::ManifestStep& s = file.steps[k];
    const std::string where = "steps[" + std::to_string(k) + "]";
    MeshedStep m;
    m.step = s.step;
    if (static_cast<std::size_t>(m.step) >= rows.size())
      throw UserError(name, where + ".step",
                      "step " + std::to_string(m.step) + " is not a row of interfaces.csv (" +
                          std::to_string(rows.size()) + " rows)");
    const sim::InterfaceRecord& row = rows[static_cast<std::size_t>(m.step)];
    m.time_s = s.time_s;
    m.inner_radius_m = s.inner_radius_m;
    m.outer_radius_m = s.outer_radius_m;
    // The manifest and interfaces.csv come from the same run: a different time means the mesh
    // folder belongs to another simulation (relative 1e-9 allows for decimal round trips).
    if (std::abs(m.time_s - row.time_s) > 1e-9 * std::max(1.0, std::abs(row.time_s)))
      throw UserError(name, where + ".time_s",
                      "time " + std::to_string(m.time_s) +
                          " s disagrees with interfaces.csv step " + std::to_string(m.step) + " (" +
                          std::to_string(row.time_s) + " s)");
    if (s.inner_exact_volume_m3) m.inner_exact_volume_m3 = *s.inner_exact_volume_m3;
    if (s.outer_exact_volume_m3) m.outer_exact_volume_m3 = *s.outer_exact_volume_m3;
    if (s.inner) m.inner = base / *s.inner;
    if (s.outer) m.outer = base / *s.outer;
    steps.push_back(std::move(m));
  }
  return steps;
}

SimulationFolder read_simulation_folder(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw UserError(dir.string(), "", "not a directory");
  SimulationFolder f;
  f.dir = dir;
  f.rows = sim::read_interfaces_csv(dir / "interfaces.csv");
  // A grid run (axisymmetric / 3D: a fields/ folder) has no 1D shell; its radii are
  // volume-equivalent spheres and its exact volumes unknown here.
  const bool grid_run = fs::is_directory(dir / "fields", ec);
  if (!grid_run && fs::exists(dir / "summary.json", ec))
    f.geometry = sim::read_shell_geometry(dir / "summary.json");
  const fs::path manifest = dir / "mesh" / "manifest.json";
  if (fs::exists(manifest, ec)) {
    f.meshed = true;
    f.steps = read_mesh_manifest(manifest, f.rows);
  }
  return f;
}

std::optional<double> exact_volume_m3(const std::optional<sim::ShellGeometry>& geometry, double r) {
  if (!geometry) return std::nullopt;
  const double ball = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  switch (geometry->geometry) {
    case sim::Geometry::sphere:
      return ball;
    case sim::Geometry::cylinder:
      return std::numbers::pi * r * r * geometry->length_m + ball;
    case sim::Geometry::planar:
      return std::nullopt;
  }
  return std::nullopt;
}

std::vector<StepReport> inspect_simulation(const SimulationFolder& folder,
                                           const ProgressCallback& progress) {
  std::vector<StepReport> out;
  const auto total = static_cast<std::int64_t>(folder.steps.size());
  for (const MeshedStep& s : folder.steps) {
    StepReport r;
    r.step = s;
    if (s.inner) {
      r.inner = inspect_obj(*s.inner);
      r.inner_exact_volume_m3 = s.inner_exact_volume_m3
                                    ? s.inner_exact_volume_m3
                                    : exact_volume_m3(folder.geometry, s.inner_radius_m);
    }
    if (s.outer) {
      r.outer = inspect_obj(*s.outer);
      r.outer_exact_volume_m3 = s.outer_exact_volume_m3
                                    ? s.outer_exact_volume_m3
                                    : exact_volume_m3(folder.geometry, s.outer_radius_m);
    }
    out.push_back(std::move(r));
    if (progress) progress(static_cast<std::int64_t>(out.size()), total);
  }
  return out;
}

namespace {
nlohmann::ordered_json surface_json(const std::optional<MeshReport>& report,
                                    const std::optional<double>& exact) {
  if (!report) return nullptr;
  nlohmann::ordered_json j = to_json(*report);
  j["exact_volume_m3"] = exact ? nlohmann::ordered_json(*exact) : nlohmann::ordered_json(nullptr);
  j["volume_error_rel"] = exact && *exact > 0
                              ? nlohmann::ordered_json((report->volume_m3 - *exact) / *exact)
                              : nlohmann::ordered_json(nullptr);
  return j;
}
}  // namespace

nlohmann::ordered_json to_json(const std::vector<StepReport>& reports) {
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  for (const StepReport& r : reports) {
    a.push_back({{"step", r.step.step},
                 {"time_s", r.step.time_s},
                 {"inner_radius_m", r.step.inner_radius_m},
                 {"outer_radius_m", r.step.outer_radius_m},
                 {"inner", surface_json(r.inner, r.inner_exact_volume_m3)},
                 {"outer", surface_json(r.outer, r.outer_exact_volume_m3)}});
  }
  return a;
}

std::string format_table(const SimulationFolder& folder, const std::vector<StepReport>& reports) {
  std::string out;
  char buf[512];
  const char* geometry = folder.geometry ? sim::to_string(folder.geometry->geometry) : "unknown";
  std::snprintf(buf, sizeof buf, "%s: %zu rows in interfaces.csv, geometry %s, %s\n",
                folder.dir.string().c_str(), folder.rows.size(), geometry,
                folder.meshed ? (std::to_string(folder.steps.size()) + " meshed steps").c_str()
                              : "not meshed (no mesh/manifest.json)");
  out += buf;
  if (!folder.meshed) {
    out += "   step       time_s    inner_r_m    outer_r_m\n";
    for (const sim::InterfaceRecord& r : folder.rows) {
      std::snprintf(buf, sizeof buf, "%7ld %12.6g %12.6g %12.6g\n", r.step, r.time_s,
                    r.inner_radius_m, r.outer_radius_m);
      out += buf;
    }
    return out;
  }
  out +=
      "   step       time_s surface   radius_m  triangles closed outward   volume_m3 vol_err_%"
      "    area_m2 min_ang max_AR bnd_e nm_e dup_v\n";
  for (const StepReport& r : reports) {
    auto line = [&](const char* name, double radius, const std::optional<MeshReport>& m,
                    const std::optional<double>& exact) {
      if (!m) {
        std::snprintf(buf, sizeof buf, "%7ld %12.6g %-7s %10.4g  (vanished)\n", r.step.step,
                      r.step.time_s, name, radius);
        out += buf;
        return;
      }
      char err[32] = "      -";
      if (exact && *exact > 0)
        std::snprintf(err, sizeof err, "%9.4f", 100.0 * (m->volume_m3 - *exact) / *exact);
      std::snprintf(buf, sizeof buf,
                    "%7ld %12.6g %-7s %10.4g %10lld %-6s %-7s %11.5g %9s %10.4g %7.2f %6.3f %5lld "
                    "%4lld %5lld\n",
                    r.step.step, r.step.time_s, name, radius, static_cast<long long>(m->triangles),
                    m->closed ? "yes" : "NO", m->outward ? (*m->outward ? "yes" : "NO") : "n/a",
                    m->volume_m3, err, m->area_m2, m->min_angle_deg, m->max_aspect_ratio,
                    static_cast<long long>(m->boundary_edges),
                    static_cast<long long>(m->non_manifold_edges),
                    static_cast<long long>(m->duplicate_vertices));
      out += buf;
    };
    line("inner", r.step.inner_radius_m, r.inner, r.inner_exact_volume_m3);
    line("outer", r.step.outer_radius_m, r.outer, r.outer_exact_volume_m3);
  }
  return out;
}

}  // namespace thaw::inspect
