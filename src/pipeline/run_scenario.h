#pragma once
// The scenario of `thaw run`: one TOML file holding the simulation sections (sim/ parses those),
// [film] (frame times, fps, GIF, caption), [mesh] (surface mesher options) and [render] (a thaw
// scene without the shell: camera, lights, floor, media, image settings, plus [render.shell]
// saying where the shell sits and which media it is made of). Every key is checked once for the
// whole file, so a typo anywhere is reported before any work starts.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "render/scene/scene_description.h"
#include "sim/scenario/scenario.h"
#include "src/mesh/mesh_options.h"

namespace thaw {
class TomlTable;
}

namespace thaw::pipeline {

struct FilmSettings {
  /// frames per second of melt.mp4
  double fps = 12.0;
  /// number of frames spread evenly over [0, duration_s] (used when time_lapse is 0)
  int frames = 48;
  /// simulated seconds per film second; > 0 overrides `frames`: frame k is at k * time_lapse / fps
  double time_lapse = 0.0;
  /// also write melt.gif
  bool gif = false;
  /// stamp "t = 12 min 30 s" on every frame
  bool caption = true;
  /// png: frames/frame_NNNNNN.png only; exr: also frame_NNNNNN.exr beside each PNG, linear half
  /// RGBA without the caption plus depth, normal and id layers (render/image/exr_io.h); the film
  /// is encoded from the PNGs either way
  enum class FramesFormat { png, exr };
  FramesFormat frames_format = FramesFormat::png;
  /// `thaw run --fps`: melt.mp4 plays at this rate instead (0 = fps). The frames' simulated
  /// times stay those of `fps`, so the simulation and meshes stay valid; with time_lapse the film
  /// then plays faster or slower than the time lapse says.
  double playback_fps = 0.0;
  double film_fps() const { return playback_fps > 0 ? playback_fps : fps; }
};

/// The one rule for a film's frame rate ([film] fps and --fps): "" if `fps` is fine, otherwise
/// the problem ("must be between ...").
std::string fps_problem(double fps);

struct ShellPlacement {
  /// where the centre of the shell (sphere centre, capsule midpoint, slab mid-plane) sits [m]
  std::array<double, 3> center{0.0, 0.0, 0.0};
  /// if set (rest_on_floor = true), the shell is lowered each frame so that its lowest point
  /// touches y = floor_y [m], as a melting piece of ice resting on a plate would
  bool rest_on_floor = false;
  double floor_y = 0.0;
  /// media names (declared in [render.media], or "vacuum")
  std::string ice_medium = "ice", water_medium = "water", outside_medium = "vacuum";
};

struct RunScenario {
  std::string source_name;  ///< file name, or "<built-in default>"
  sim::Scenario simulation;
  FilmSettings film;
  mesh::MeshOptions mesh;
  render::SceneDescription scene;  ///< everything but the shell
  ShellPlacement shell;
  /// the scenario sets [render.camera]; otherwise the frames use the built-in framing camera
  /// (src/pipeline/frame_camera.h)
  bool camera_set = false;
  /// --size / --spp replaced [render.image]'s settings (render_overrides.h): a run with other
  /// settings than its folder's finals is then a preview (preview_folder.h)
  bool image_overridden = false;
  /// canonical text of each section, for fingerprinting what a stage depends on
  std::string simulation_text, film_text, mesh_text, render_text;
};

/// The built-in default scenario (data/scenarios/default.toml, embedded).
RunScenario default_run_scenario();
std::string default_run_scenario_text();
/// Parses a whole scenario; throws thaw::UserError(file, "line N, key 'a.b'", problem).
RunScenario parse_run_scenario(const TomlTable& root);
RunScenario read_run_scenario(const std::filesystem::path& path);

/// Simulated times of the film frames: exactly k * step (computed as products).
std::vector<double> frame_times(const RunScenario& scenario);

}  // namespace thaw::pipeline
