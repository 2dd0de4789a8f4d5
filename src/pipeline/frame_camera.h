#pragma once
// The built-in camera of `thaw run` when the scenario sets no [render.camera]: it frames the
// shell's largest extent over the whole run (so it is the same for every frame: no camera
// motion), seen from a fixed three-quarter view slightly from above, the shell's bounding box
// filling a fixed share of the frame. Deterministic: plain arithmetic on the run's radii.
// Knows nothing of files or of the renderer beyond the camera description.
#include <array>
#include <vector>

#include "render/scene/scene_description.h"
#include "sim/format/interface_history.h"
#include "src/pipeline/run_scenario.h"

namespace thaw::pipeline {

struct AutoCameraSettings {
  /// full vertical field of view [degrees]
  double vertical_fov_deg = 35.0;
  /// elevation of the view direction above the horizontal [degrees] and its azimuth from +z
  /// towards +x [degrees] (a slab, whose faces look along x, is seen at an angle, not edge-on)
  double elevation_deg = 17.0, azimuth_deg = 30.0;
  /// share of the frame's half-width and half-height the bounding box may fill
  double fill = 0.55;
};

/// Axis-aligned box [m].
struct Box3 {
  std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
};

/// The box holding the shell's outer surface at its largest over `rows` (sphere, capsule along z,
/// slab with faces along x, as docs/mesh.md centres them), moved to `center`, or resting on
/// y = floor_y if `rest_on_floor` (its lowest point there, as the frames place it).
Box3 shell_extent(const std::vector<sim::InterfaceRecord>& rows, const sim::ShellGeometry& geometry,
                  const std::array<double, 3>& center, bool rest_on_floor, double floor_y);

/// Camera looking at the box's centre from the settings' direction, at the smallest distance at
/// which every corner of the box projects within `fill` of the frame (width / height = aspect).
render::CameraDescription framing_camera(const Box3& box, double aspect,
                                         const AutoCameraSettings& settings = {});

/// The camera of every frame of a run: the scenario's [render.camera] if it sets one, otherwise
/// framing_camera() of the shell's extent over `rows` at the image's aspect ratio.
render::CameraDescription run_camera(const RunScenario& sc,
                                     const std::vector<sim::InterfaceRecord>& rows,
                                     const sim::ShellGeometry& geometry);

}  // namespace thaw::pipeline
