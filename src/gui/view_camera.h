#pragma once
// The 3D view's camera as plain numbers, and the moves the mouse makes with it (orbit, pan, zoom)
// and the framing of the shell, computed on the GUI thread: the view's render thread
// (view_render_thread.h) only applies the camera it is given, so the mouse never waits for a
// draw. The moves are those of VTK's trackball camera style (vtkInteractorStyleTrackballCamera:
// vtkCamera::Azimuth, Elevation, OrthogonalizeViewUp, Dolly; vtkRenderer::ResetCamera for the
// framing), in scene units and degrees. Knows nothing of Qt or VTK.
#include <array>

namespace thaw::gui {

struct ViewCamera {
  std::array<double, 3> position, focal_point, view_up;
  double vertical_fov_deg;
};

/// Rotates the camera about its focal point: `azimuth_deg` about its view-up vector, then
/// `elevation_deg` about the axis to its left (a positive elevation moves the camera up), then
/// makes the view-up orthogonal to the direction of projection (vtkCamera's Azimuth, Elevation,
/// OrthogonalizeViewUp). The distance to the focal point is unchanged.
ViewCamera orbit(const ViewCamera& camera, double azimuth_deg, double elevation_deg);

/// Moves the position and the focal point together by `right` view heights to the camera's
/// right and `up` view heights along its view-up (a view height: what the vertical field of view
/// spans at the focal point's distance).
ViewCamera pan(const ViewCamera& camera, double right, double up);

/// Moves the camera along its direction of projection so that its distance to the focal point
/// is divided by `factor` (> 1: closer; vtkCamera::Dolly).
ViewCamera dolly(const ViewCamera& camera, double factor);

/// The camera moved along its current direction so that the sphere about the axis-aligned box
/// `bounds` (xmin, xmax, ymin, ymax, zmin, zmax) just fits the field of view of a view
/// `aspect` = width / height wide, its focal point the box's centre (vtkRenderer::ResetCamera).
ViewCamera frame_bounds(const ViewCamera& camera, const std::array<double, 6>& bounds,
                        double aspect);

}  // namespace thaw::gui
