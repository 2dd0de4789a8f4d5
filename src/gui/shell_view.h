#pragma once
// The 3D view: one shell step's inner and outer surfaces drawn as `thaw inspect --screenshot`
// draws them (src/inspect/surface_actor.h: translucent ice, blue water), in VTK's Qt widget,
// orbited with the mouse. Showing a step replaces the two actors and keeps the camera, so
// scrubbing through a run shows the shell shrinking in place.
#include <QVTKOpenGLNativeWidget.h>
#include <vtkSmartPointer.h>

#include <array>

#include "src/gui/shell_step.h"

class vtkRenderer;
class vtkActor;
class vtkTextActor;

namespace thaw::gui {

class ShellView : public QVTKOpenGLNativeWidget {
  Q_OBJECT
 public:
  explicit ShellView(QWidget* parent = nullptr);
  /// Shows `step`'s surfaces; the camera is framed on them when `frame` (a new scenario). While
  /// `moving` (the time slider is dragged) the outer surface is drawn without its triangle
  /// edges: with software OpenGL (llvmpipe) the edges' extra pass made each draw 2.5x slower
  /// (bench/gui/bench_gui); settle() draws them again once the slider rests.
  void show_step(const ShellStep& step, bool frame, bool moving = false);
  /// Draws the shown step with its triangle edges (after a drag of the time slider).
  void settle();
  /// The view's camera in the meshes' frame (the shell's core at the origin) [m, degrees].
  struct ViewCamera {
    std::array<double, 3> position, focal_point, view_up;
    double vertical_fov_deg;
  };
  ViewCamera camera() const;
  /// Sets the view's camera (tests; then call report_camera() as an orbit would).
  void set_camera(const ViewCamera& camera);
  /// Emits cameraMoved with the current camera (called when an orbit, pan or zoom ends).
  void report_camera();
  /// Triangles drawn (both surfaces), for tests.
  long triangles() const { return m_triangles; }
  /// Whether the outer surface is drawn with its triangle edges (false while the slider moves).
  bool edges_shown() const;

 signals:
  /// The user orbited, panned or zoomed the view (the window writes it back as the scene camera).
  void cameraMoved();

 private:
  vtkSmartPointer<vtkRenderer> m_renderer;
  vtkSmartPointer<vtkActor> m_outer, m_inner;
  vtkSmartPointer<vtkTextActor> m_label;
  long m_triangles = 0;
};

}  // namespace thaw::gui
