#pragma once
// DIR/handoff/paraview_state.py: a ParaView Python state that opens the run's meshes.pvd (the
// inspect stage's series, placed where the film shows the shell) and looks at it through the
// camera the frames were rendered with (VTK's view angle is the vertical field of view, as
// thaw's), at the frames' size. `pvpython paraview_state.py [--frame N] [--screenshot PATH]
// [--mask PATH]`, or File > Load State in ParaView (both need ParaView's Python; on a machine that
// builds thaw, scripts/setup unpacks it beside libvtk9-dev: docs/handoff.md). Beside it
// DIR/handoff/paraview_camera.pvcc, the same camera as ParaView's camera configuration (the camera
// dialog's Load, no Python needed). A run whose water flows (fields.pvd with velocity_m_s) also
// shows the velocity: arrows at the cell centres, oriented and scaled by it (the fastest as long
// as a twentieth of the fields' box) and coloured by the speed (left out of --mask). Knows
// nothing about VTK: it writes text.
#include <filesystem>

#include "render/scene/scene_description.h"

namespace thaw::pipeline {

/// Writes paraview_state.py at `path` and paraview_camera.pvcc beside it; `velocity`: the run
/// folder's fields.pvd holds the water's velocity, shown as arrows.
void write_paraview_state(const std::filesystem::path& path,
                          const render::CameraDescription& camera, int width, int height,
                          bool velocity = false);

}  // namespace thaw::pipeline
