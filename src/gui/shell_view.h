#pragma once
// The 3D view: the frame's scene in scene coordinates, in VTK's Qt widget, orbited with the
// mouse: one shell step's inner and outer surfaces drawn as `thaw inspect --screenshot` draws
// them (src/inspect/surface_actor.h: translucent ice, blue water) where the frames place them,
// and the scene's other objects and lights (scene_props.h), seen through the frame's camera
// until the user moves it. Showing a step replaces the shell's two actors and keeps the camera,
// so scrubbing through a run shows the shell shrinking in place.
#include <QVTKOpenGLNativeWidget.h>
#include <vtkSmartPointer.h>

#include <array>
#include <string>
#include <vector>

#include "src/gui/scene_props.h"
#include "src/gui/shell_step.h"

class vtkRenderer;
class vtkActor;
class vtkTextActor;

namespace thaw::gui {

class ShellView : public QVTKOpenGLNativeWidget {
  Q_OBJECT
 public:
  explicit ShellView(QWidget* parent = nullptr);
  /// Shows `step`'s surfaces moved by `offset` (where the frame places the shell's core) [m];
  /// the camera is framed on them when `frame` and no scene camera was set yet (set_scene).
  /// While `moving` (the time slider is dragged) the view is drawn quick (set_quick) until
  /// settle().
  void show_step(const ShellStep& step, const std::array<double, 3>& offset, bool frame,
                 bool moving = false);
  /// Shows the scene's other objects and lights (their actors swapped when their key differs)
  /// and, when it differs from the view's, the frame's camera; draws only if anything changed.
  void set_scene(const SceneProps& props);
  /// The scene objects and lights drawn (tests).
  std::size_t scene_objects() const { return m_scene_objects; }
  std::size_t scene_lights() const { return m_scene_lights; }
  /// Quick drawing, while the slider is dragged or the view orbited: the outer surface without its
  /// triangle edges (with software OpenGL, llvmpipe, their extra pass made each draw 2.5x
  /// slower) and the floor in its checker's mean colour (llvmpipe's texture sampling was most of
  /// a draw's CPU time: bench/gui/bench_gui). Takes effect at the next draw.
  void set_quick(bool quick);
  /// Draws the view at rest again (edges, filtered textures) if it was quick.
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
  std::vector<vtkSmartPointer<vtkActor>> m_scene;
  std::vector<vtkSmartPointer<vtkTexture>> m_scene_textures;
  std::vector<std::array<double, 3>> m_quick_colors;
  std::string m_scene_key;
  std::size_t m_scene_objects = 0, m_scene_lights = 0;
  bool m_scene_camera = false;
  bool m_quick = false;
  /// between the interactor's start and end of an orbit, pan or zoom
  bool m_interacting = false;
};

}  // namespace thaw::gui
