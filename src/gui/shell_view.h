#pragma once
// The 3D view: the frame's scene in scene coordinates, orbited with the mouse: one shell step's
// inner and outer surfaces drawn as `thaw inspect --screenshot` draws them
// (src/inspect/surface_actor.h: translucent ice, blue water) where the frames place them, and the
// scene's other objects and lights (scene_props.h), seen through the frame's camera until the
// user moves it. Showing a step replaces the shell's two actors and keeps the camera, so
// scrubbing through a run shows the shell shrinking in place.
//
// A plain widget on Qt's raster backing store: it keeps what the view shows (the actors, the
// camera, the quick look) and asks its render thread (view_render_thread.h) for a frame after
// every change; the thread draws with VTK in its own OpenGL context and hands back an image, which
// this widget paints. So the GUI thread never compiles a shader nor waits for a draw (with Mesa's
// llvmpipe a first run's shader compiles were 100-150 ms each, a draw 45-60 ms). The mouse moves
// the camera here (view_camera.h, VTK's trackball moves) and asks for the next frame; while a
// draw is in progress only the latest request waits.
#include <vtkSmartPointer.h>
#include <QElapsedTimer>
#include <QImage>
#include <QPoint>
#include <QWidget>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "src/gui/scene_props.h"
#include "src/gui/shell_step.h"
#include "src/gui/view_camera.h"

class vtkActor;
class vtkTexture;
class QTimer;

namespace thaw::gui {

class ViewRenderThread;

class ShellView : public QWidget {
  Q_OBJECT
 public:
  explicit ShellView(QWidget* parent = nullptr);
  ~ShellView() override;
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
  /// Quick drawing, while the slider is dragged or the view orbited (ViewFrame::quick). Takes
  /// effect at the next draw.
  void set_quick(bool quick);
  /// Draws the view at rest again (edges, filtered textures) if it was quick: with the next
  /// scene (set_scene), or kSettleMs from now if none comes sooner (the window asks for the new
  /// camera's or step's scene meanwhile, whose draw is then the only one at rest).
  void settle();
  static constexpr int kSettleMs = 400;
  /// The view's camera in scene coordinates [m, degrees].
  using ViewCamera = gui::ViewCamera;
  ViewCamera camera() const { return m_camera; }
  /// Sets the view's camera and draws (an orbit step; tests).
  void set_camera(const ViewCamera& camera);
  /// An orbit, pan or zoom begins (drawn quick while it lasts) and ends (drawn at rest, its
  /// camera reported: cameraMoved), as the mouse's press and release do.
  void begin_interaction();
  void end_interaction();
  /// Emits cameraMoved with the current camera (called when an orbit, pan or zoom ends).
  void report_camera();
  /// Frames of the view painted so far (bench_gui).
  long frames_shown() const { return m_frames_shown; }
  /// Triangles drawn (both surfaces), for tests.
  long triangles() const { return m_triangles; }
  /// Whether the view is drawn quick (set_quick) now.
  bool quick() const { return m_quick; }
  /// Whether the outer surface is drawn with its triangle edges: at rest, and only where its
  /// triangles' mean edge is at least kEdgeMinPx on the screen (closer, 1-pixel edge lines read
  /// as salt-and-pepper noise over the ice and the water behind it, not as a mesh).
  bool edges_shown() const;
  static constexpr double kEdgeMinPx = 12;
  /// Whether the view waits for the frame of its latest request (false without a display, where
  /// the view stays undrawn).
  bool drawing() const { return m_render && m_received < m_requested; }
  /// Actors (and the label) in the latest request (tests).
  std::size_t drawn_props() const;
  /// The last frame received (null before the first): what the view shows.
  QImage image() const { return m_frame; }

 signals:
  /// The user orbited, panned or zoomed the view (the window writes it back as the scene camera).
  void cameraMoved();

 protected:
  void paintEvent(QPaintEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;

 private:
  /// Asks the render thread for a frame of what the view holds now.
  void draw();
  /// A frame of request `serial` arrived: painted now.
  void on_frame(const QImage& image, quint64 serial);
  /// Ends a pending settle(): the at-rest look, drawn by the caller.
  void settle_now();

  ViewRenderThread* m_render = nullptr;  // null without a display
  std::uint64_t m_requested = 0, m_received = 0, m_painted = 0;
  QImage m_frame;
  long m_frames_shown = 0;
  QTimer* m_settle_timer = nullptr;
  bool m_settle_pending = false;
  ViewCamera m_camera{{0.55, 0.38, 0.75}, {0, 0, 0}, {0, 1, 0}, 30};
  vtkSmartPointer<vtkActor> m_outer, m_inner;
  std::array<double, 3> m_offset{0, 0, 0};
  std::string m_label;
  long m_triangles = 0;
  /// the outer surface's mean triangle edge [m]
  double m_edge_length_m = 0;
  std::vector<vtkSmartPointer<vtkActor>> m_scene;
  std::vector<vtkSmartPointer<vtkTexture>> m_scene_textures;
  std::vector<std::array<double, 3>> m_quick_colors;
  std::string m_scene_key;
  std::size_t m_scene_objects = 0, m_scene_lights = 0;
  bool m_scene_camera = false;
  bool m_quick = false;
  /// between the start and end of an orbit, pan or zoom
  bool m_interacting = false;
  /// the mouse button dragging (Qt::NoButton: none) and its last position
  Qt::MouseButton m_button = Qt::NoButton;
  QPoint m_last;
};

}  // namespace thaw::gui
