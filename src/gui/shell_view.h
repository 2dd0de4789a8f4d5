#pragma once
// The 3D view: one shell step's inner and outer surfaces drawn as `thaw inspect --screenshot`
// draws them (src/inspect/surface_actor.h: translucent ice, blue water), in VTK's Qt widget,
// orbited with the mouse. Showing a step replaces the two actors and keeps the camera, so
// scrubbing through a run shows the shell shrinking in place.
#include <QVTKOpenGLNativeWidget.h>
#include <vtkSmartPointer.h>

#include "src/gui/shell_step.h"

class vtkRenderer;
class vtkActor;
class vtkTextActor;

namespace thaw::gui {

class ShellView : public QVTKOpenGLNativeWidget {
  Q_OBJECT
 public:
  explicit ShellView(QWidget* parent = nullptr);
  /// Shows `step`'s surfaces; the camera is framed on them when `frame` (a new scenario).
  void show_step(const ShellStep& step, bool frame);
  /// Triangles drawn (both surfaces), for tests.
  long triangles() const { return m_triangles; }

 private:
  vtkSmartPointer<vtkRenderer> m_renderer;
  vtkSmartPointer<vtkActor> m_outer, m_inner;
  vtkSmartPointer<vtkTextActor> m_label;
  long m_triangles = 0;
};

}  // namespace thaw::gui
