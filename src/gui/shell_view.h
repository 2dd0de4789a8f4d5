#pragma once
// The 3D view: the frame's scene in scene coordinates, in VTK's Qt widget, orbited with the
// mouse: one shell step's inner and outer surfaces drawn as `thaw inspect --screenshot` draws
// them (src/inspect/surface_actor.h: translucent ice, blue water) where the frames place them,
// and the scene's other objects and lights (scene_props.h), seen through the frame's camera
// until the user moves it. Showing a step replaces the shell's two actors and keeps the camera,
// so scrubbing through a run shows the shell shrinking in place.
//
// The view is an OpenGL window of its own (VTK's QVTKOpenGLWindow, a QOpenGLWindow) in a window
// container (QWidget::createWindowContainer), not an OpenGL widget (QVTKOpenGLNativeWidget, a
// QOpenGLWidget): a QOpenGLWidget makes Qt 5 composite the whole top-level window through OpenGL
// on every repaint of any widget in it (the raster backing store uploaded as a texture, blended
// with the widget's, swapped: with software OpenGL, llvmpipe, a full-window draw per repaint),
// and makes its OpenGL context and first paint inside the window's show(). In a container the
// rest of the window stays on Qt's raster backing store; the OpenGL work is the view's own child
// window's, its context made in its first expose, a turn of its own.
#include <vtkSmartPointer.h>
#include <QElapsedTimer>
#include <QWidget>

#include <array>
#include <deque>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "src/gui/scene_props.h"
#include "src/gui/shell_step.h"

class QVTKInteractor;
class vtkRenderWindow;
class vtkRenderer;
class vtkActor;
class vtkProp;
class vtkTextActor;
class QTimer;

namespace thaw::gui {

/// What decides the shaders and pipeline state an actor is drawn with (see Staged below): actors
/// with equal looks draw with the programs the first of them compiled.
std::string look_of(vtkProp* prop);

class ViewWindow;

class ShellView : public QWidget {
  Q_OBJECT
 public:
  explicit ShellView(QWidget* parent = nullptr);
  /// VTK's render window and its interactor (the view's OpenGL window's).
  vtkRenderWindow* renderWindow() const;
  QVTKInteractor* interactor() const;
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
  /// Draws the view at rest again (edges, filtered textures) if it was quick: with the next
  /// scene (set_scene), or kSettleMs from now if none comes sooner (the window asks for the new
  /// camera's or step's scene meanwhile, whose draw is then the only one at rest).
  void settle();
  static constexpr int kSettleMs = 400;
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
  /// Frames of the view's draws shown on the screen so far (swapped: bench_gui).
  long frames_shown() const { return m_frames_shown; }
  /// Warm-up turns that began before the last draw's frame was shown and kFrameWaitMs had
  /// passed (tests: none, else two draws made one long block of the GUI thread).
  long early_turns() const { return m_early_turns; }
  /// Triangles drawn (both surfaces), for tests.
  long triangles() const { return m_triangles; }
  /// Whether the outer surface is drawn with its triangle edges (false while the slider moves).
  bool edges_shown() const;
  /// Whether some actors still wait for their turn to be drawn (warm-up, below). Never before
  /// the first paint: the turns start with it (a platform without OpenGL never paints the view).
  bool warming_up() const { return m_painted && !m_staged.empty(); }
  /// Holds every look not drawn yet (the view shows what it has, at first its plain background)
  /// until release(): while a child process fills Mesa's shader cache (shader_warmup.h), so
  /// that the turns below then load the compiled shaders instead of compiling them here.
  void hold();
  /// Ends hold(): the held looks are drawn in turns as below.
  void release();
  bool held() const { return m_held; }
  /// The most looks first drawn in one draw (tests; warm-up, below).
  int most_new_looks_per_draw() const { return m_most_new_looks; }
  /// Adds one actor of each look among `catalog`'s actors (look_catalog(), scene_props.h) and
  /// their copies without texture (the look while the view is drawn quick) that was not drawn
  /// yet, in turns as new looks are: the --warm-shaders child draws every look an edit can bring
  /// (shader_warmup.h). Returns how many it added.
  std::size_t add_catalog(const SceneProps& catalog);
  /// The looks drawn so far (tests).
  const std::set<std::string>& looks() const { return m_looks; }
  /// Actors (and the label) in the renderer now (tests).
  std::size_t drawn_props() const;
  /// The view drawn now, at its size in pixels (the window's screenshot: QWidget::grab does not
  /// see the OpenGL child window's pixels). Null before the first paint.
  QImage image();

 signals:
  /// The user orbited, panned or zoomed the view (the window writes it back as the scene camera).
  void cameraMoved();

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  // Warm-up. With software OpenGL (Mesa llvmpipe) the first draw of each new look (shader
  // program and pipeline state: translucent, textured, with edges, the label, the gradient)
  // compiles its shaders with LLVM, 10-40 ms of CPU on the GUI thread each; drawing the whole
  // scene at once blocked the GUI thread for 0.3-0.9 s at start-up. So an actor of a look not
  // drawn yet is added alone: at most one new look per draw, the others wait for the next
  // event-loop turns (m_stage_timer), in order. Actors of looks drawn before are added at once,
  // so a slider move swaps its two surfaces in one draw.
  struct Staged {
    std::string look;
    vtkSmartPointer<vtkProp> prop;  // null for a setting of the renderer (gradient, label)
    std::function<void()> apply;
    /// applied when `prop` is removed before its turn (else dropped with it)
    bool apply_when_removed = false;
  };
  /// Adds `prop` as stage() does.
  void add_prop(vtkProp* prop);
  /// Applies `apply` (adding `prop`, or a new look of the renderer itself) now if `look` was
  /// drawn before or is the first new look since the last draw, else queues it.
  void stage(const std::string& look, std::function<void()> apply, vtkProp* prop = nullptr,
             bool apply_when_removed = false);
  void remove_prop(vtkProp* prop);
  /// Draws (every actor added so far) and starts the next warm-up turn if any waits.
  void draw();
  /// One warm-up turn: the queued additions up to the second new look, then a draw.
  void advance();
  /// Starts the next warm-up turn (the last draw's frame has reached the window, or waited
  /// kFrameWaitMs).
  void next_turn();
  static constexpr int kFrameWaitMs = 100;
  /// Ends a pending settle(): the at-rest look, drawn by the caller.
  void settle_now();
  /// The OpenGL window's first paint (its context made, the plain background shown) lets the
  /// warm-up begin.
  void first_frame();

  ViewWindow* m_window = nullptr;
  std::deque<Staged> m_staged;
  std::set<std::string> m_looks;
  int m_new_looks = 0, m_most_new_looks = 0;
  bool m_painted = false;
  bool m_held = false;
  QTimer* m_stage_timer = nullptr;
  QTimer* m_frame_timer = nullptr;
  QTimer* m_settle_timer = nullptr;
  bool m_settle_pending = false;
  vtkSmartPointer<vtkRenderer> m_renderer;
  vtkSmartPointer<vtkActor> m_outer, m_inner;
  vtkSmartPointer<vtkTextActor> m_label;
  long m_triangles = 0;
  long m_frames_shown = 0, m_frames_at_draw = 0, m_early_turns = 0;
  QElapsedTimer m_since_draw;  // since the last draw
  std::vector<vtkSmartPointer<vtkActor>> m_scene;
  std::vector<vtkSmartPointer<vtkActor>> m_catalog;
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
