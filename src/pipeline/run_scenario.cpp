#include "src/pipeline/run_scenario.h"

#include <cmath>
#include <cstdio>

#include "base/error.h"
#include "base/format/toml_table.h"
#include "render/format/scene_parser.h"
#include "render/scene/scene_rules.h"
#include "sim/format/scenario_file.h"
#include "sim/grid/grid_rules.h"
#include "src/pipeline/film_size.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;

namespace {

const char* const kBuiltInName = "<built-in data/scenarios/default.toml>";

FilmSettings parse_film(const TomlTable& t) {
  FilmSettings f;
  f.fps = t.get_double("fps", f.fps);
  if (const std::string problem = fps_problem(f.fps); !problem.empty()) t.fail("fps", problem);
  if (t.has("frames") && t.has("time_lapse"))
    t.fail("time_lapse", "give either frames or time_lapse, not both");
  const std::int64_t frames = t.get_int("frames", f.frames);
  if (frames < 1 || frames > 100000)
    t.fail("frames", "must be between 1 and 100000 (got " + std::to_string(frames) + ")");
  f.frames = static_cast<int>(frames);
  if (t.has("time_lapse"))
    f.time_lapse = t.require_positive("time_lapse", t.get_double("time_lapse"));
  f.gif = t.get_bool("gif", f.gif);
  f.caption = t.get_bool("caption", f.caption);
  const std::string format = t.get_string("frames_format", "png");
  if (format == "exr")
    f.frames_format = FilmSettings::FramesFormat::exr;
  else if (format != "png")
    t.fail("frames_format", "must be \"png\" or \"exr\" (got \"" + format + "\")");
  return f;
}

mesh::MeshOptions parse_mesh(const TomlTable& t, const std::string& source) {
  mesh::MeshOptions m;
  m.edge_length_m = t.get_double("edge_length_m", m.edge_length_m);
  m.triangles = t.get_int("triangles", m.triangles);
  m.angle_deg = t.get_double("angle_deg", m.angle_deg);
  m.distance_m = t.get_double("distance_m", m.distance_m);
  m.relative_distance = t.get_double("relative_distance", m.relative_distance);
  m.min_radius_m = t.get_double("min_radius_m", m.min_radius_m);
  m.max_triangles = t.get_int("max_triangles", m.max_triangles);
  m.normals = t.get_bool("normals", m.normals);
  m.keep_distance = t.has("distance_m") || t.has("relative_distance");
  try {
    mesh::validate(m);
  } catch (const UserError& e) {
    // validate() names the option; add the file and the section.
    throw UserError(source, "key 'mesh." + e.where() + "'", e.problem());
  }
  return m;
}

ShellPlacement parse_shell(const TomlTable& t) {
  ShellPlacement s;
  s.center = t.get_vec3("center", s.center);
  if (t.has("floor_y")) {
    s.rest_on_floor = true;
    s.floor_y = t.get_double("floor_y");
  }
  s.ice_medium = t.get_string("ice_medium", s.ice_medium);
  s.water_medium = t.get_string("water_medium", s.water_medium);
  s.outside_medium = t.get_string("outside_medium", s.outside_medium);
  return s;
}

/// The finest detail of the shell's meshes [m]: the mesher's edge length (given, or automatic:
/// a twelfth of the shell's radius, src/mesh/mesh_options.h), or a grid run's cell.
double shell_detail_m(const RunScenario& r) {
  if (r.mesh.edge_length_m > 0) return r.mesh.edge_length_m;
  if (r.simulation.grid != sim::GridGeometry::none) return sim::effective_cell_size_m(r.simulation);
  return r.simulation.outer_radius_m / 12;
}

/// [render.shell] center and floor_y move the shell's meshes; far from the origin single
/// precision cannot hold them (the class of a floor at y = 2^31): the scene's placement rule,
/// reported at the key that moved it.
void check_shell_placement(const TomlTable& shell, const RunScenario& r) {
  const double size_m =
      r.simulation.grid != sim::GridGeometry::none ? 0.0 : r.simulation.outer_radius_m;
  const double detail_m = shell_detail_m(r);
  for (int k = 0; k < 3; ++k)
    if (const auto p = render::placement_problem(std::abs(r.shell.center[k]) + size_m, detail_m))
      shell.fail("center", "the shell " + *p);
  if (r.shell.rest_on_floor)
    if (const auto p = render::placement_problem(std::abs(r.shell.floor_y) + 2 * size_m, detail_m))
      shell.fail("floor_y", "the shell " + *p);
}

void check_medium_declared(const TomlTable& shell, const render::SceneDescription& scene,
                           const char* key, const std::string& name) {
  if (name == "vacuum") return;
  for (const auto& m : scene.media)
    if (m.name == name) return;
  shell.fail(key, "medium '" + name + "' is not declared in [render.media]");
}

}  // namespace

std::string fps_problem(double fps) {
  // Players handle up to a few hundred frames per second; above that a typo is likelier.
  // Below 0.01 (a frame per 100 s) ffmpeg cannot parse the rate: 1e-300 was accepted and
  // the film stage failed after every frame was rendered.
  constexpr double kMinFps = 0.01, kMaxFps = 240;
  if (fps >= kMinFps && fps <= kMaxFps) return "";
  char buf[128];
  std::snprintf(buf, sizeof buf, "must be between %g and %g frames per second (got %g)", kMinFps,
                kMaxFps, fps);
  return buf;
}

RunScenario parse_run_scenario(const TomlTable& root) {
  RunScenario r;
  r.source_name = root.source_name();
  const fs::path base_dir = fs::path(root.source_name()).parent_path();

  r.simulation = sim::parse_scenario(root, {"film", "mesh", "render"});
  for (const char* section : {"simulation", "shell", "shape", "water", "ice", "inner_boundary",
                              "outer_boundary", "materials"})
    if (auto t = root.optional_table(section))
      r.simulation_text += std::string(section) + "\n" + t->canonical_text() + "\n";

  const auto film = root.optional_table("film");
  if (film) {
    r.film = parse_film(*film);
    r.film_text = film->canonical_text();
  }
  const auto mesh_table = root.optional_table("mesh");
  if (mesh_table) {
    r.mesh = parse_mesh(*mesh_table, root.source_name());
    r.mesh_text = mesh_table->canonical_text();
  }
  const auto render_table = root.optional_table("render");
  if (!render_table) {
    // A simulation-only scenario renders with the built-in look.
    const RunScenario builtin = default_run_scenario();
    r.scene = builtin.scene;
    r.shell = builtin.shell;
    r.render_text = builtin.render_text;
    r.camera_set = builtin.camera_set;
  } else {
    r.scene = render::parse_scene_table(*render_table, base_dir, /*camera_optional=*/true);
    r.render_text = render_table->canonical_text();
    r.camera_set = render_table->optional_table("camera").has_value();
    const auto shell = render_table->optional_table("shell");
    if (shell) {
      r.shell = parse_shell(*shell);
      check_shell_placement(*shell, r);
      check_medium_declared(*shell, r.scene, "ice_medium", r.shell.ice_medium);
      check_medium_declared(*shell, r.scene, "water_medium", r.shell.water_medium);
      check_medium_declared(*shell, r.scene, "outside_medium", r.shell.outside_medium);
    } else {
      for (const auto& name : {r.shell.ice_medium, r.shell.water_medium}) {
        bool found = false;
        for (const auto& m : r.scene.media) found = found || m.name == name;
        if (!found)
          render_table->fail("media", "the shell needs a medium named '" + name +
                                          "' (or set [render.shell] ice_medium / water_medium)");
      }
    }
  }
  root.check_no_unknown_keys();
  check_film_size(root, r);  // a radius in centimetres is refused here, naming metres

  const auto times = frame_times(r);
  if (times.size() < 1) root.fail("film", "no frames");
  return r;
}

RunScenario read_run_scenario(const fs::path& path) {
  return parse_run_scenario(TomlTable::parse_file(path));
}

std::string default_run_scenario_text() {
  return sim::default_scenario_text();
}

RunScenario default_run_scenario() {
  return parse_run_scenario(TomlTable::parse_string(default_run_scenario_text(), kBuiltInName));
}

std::vector<double> frame_times(const RunScenario& s) {
  const double duration = s.simulation.duration_s;
  std::vector<double> times;
  if (s.film.time_lapse > 0) {
    const double step = s.film.time_lapse / s.film.fps;
    const long n = static_cast<long>(std::floor(duration / step * (1 + 1e-12))) + 1;
    for (long k = 0; k < n; ++k) times.push_back(std::min(duration, k * step));
  } else if (s.film.frames == 1) {
    times.push_back(0.0);
  } else {
    const int n = s.film.frames;
    for (int k = 0; k < n; ++k) times.push_back(k == n - 1 ? duration : duration * k / (n - 1));
  }
  return times;
}

}  // namespace thaw::pipeline
