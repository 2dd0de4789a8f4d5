#pragma once
// The 3D view's render thread: the only thread that draws with VTK, so that no OpenGL work (Mesa
// llvmpipe compiling shaders with LLVM, 100-150 ms each on a machine's first run, and waiting
// for its rasterizer threads, 45-60 ms a draw) ever runs on the GUI thread. It owns VTK's
// offscreen render window (an OpenGL context of its own on its own X display connection), the
// renderer, its lights, background and label. The GUI thread describes a frame (ViewFrame: the
// actors, their placement, the camera, the size) and requests it; the thread takes the latest
// request (one not yet started is replaced by a newer one: frames never queue up), applies it,
// draws, reads the pixels back and hands the image to the GUI thread (frameReady), which only
// paints it. Actors made elsewhere (the preview's and the simulation's threads) are touched only
// here once requested; those no one else holds any more have their OpenGL resources released
// here, in the context that made them. Knows nothing of the window's widgets.
#include <vtkSmartPointer.h>
#include <QImage>
#include <QObject>

#include <array>
#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "src/gui/view_camera.h"

class vtkActor;
class vtkTexture;
class QSocketNotifier;

namespace thaw::gui {

/// What one frame of the 3D view shows. Made on the GUI thread; its actors are then changed
/// (placement, quick look) only by the render thread.
struct ViewFrame {
  struct Placed {
    vtkSmartPointer<vtkActor> actor;
    std::array<double, 3> position;  // the actor's translation [m]
  };
  /// the scene's objects and lights (scene_props.h), then the shell: its inner surface (opaque
  /// water) and outer surface (translucent ice, drawn after it: blended in drawing order)
  std::vector<vtkSmartPointer<vtkActor>> scene;
  /// per scene actor: its texture (null: none) and the colour drawn instead while quick
  std::vector<vtkSmartPointer<vtkTexture>> textures;
  std::vector<std::array<double, 3>> quick_colors;
  std::vector<Placed> shell;
  /// the outer surface (one of `shell`)
  vtkSmartPointer<vtkActor> outer;
  /// Drawn quick (while the slider moves or the view is orbited): each textured actor in its
  /// texture's mean colour (llvmpipe's texture sampling was most of a draw's CPU time).
  bool quick = false;
  /// The outer surface drawn with its triangle edges (ShellView decides: never while quick,
  /// where their extra pass made a draw 2.5x slower with llvmpipe, nor when they are too close
  /// on the screen).
  bool edges = false;
  std::string label;
  ViewCamera camera{};
  /// in pixels
  int width = 0, height = 0;
  std::uint64_t serial = 0;
};

/// The render thread's nice value: below the GUI thread's 0, above the preview's renders.
constexpr int kViewNice = 5;

class ViewRenderThread : public QObject {
  Q_OBJECT
 public:
  /// Starts the thread, which makes its render window and OpenGL context at once. Make it on the
  /// GUI thread: frameReady is emitted there.
  explicit ViewRenderThread(QObject* parent = nullptr);
  /// Drops a request not started, waits for the draw in progress, releases every OpenGL resource
  /// on the thread and joins it.
  ~ViewRenderThread() override;
  ViewRenderThread(const ViewRenderThread&) = delete;
  ViewRenderThread& operator=(const ViewRenderThread&) = delete;
  /// Requests `frame`, replacing a request the thread has not started yet. Never waits for the
  /// render thread (no lock is shared with it: a lock it held while waiting for a core under load
  /// would stop the GUI thread too).
  void request(ViewFrame frame);
  /// Frames drawn so far (any thread).
  long frames_drawn() const { return m_drawn; }

 signals:
  /// The frame of request `serial` drawn (emitted on the GUI thread when the render thread
  /// hands it over; a newer frame handed over meanwhile replaces it). Rows top-down, as Qt's.
  void frameReady(QImage image, quint64 serial);

 private:
  struct Scene;  // the thread's VTK objects
  struct Drawn {
    QImage image;
    quint64 serial;
  };
  void run();
  /// The GUI thread: takes the frame the render thread handed over (its eventfd was written).
  void take_frame();
  // Both ways without a lock: the latest request and the latest frame are single slots swapped
  // atomically; the render thread sleeps on its slot (a futex wait, C++20 atomic wait), the GUI
  // thread's event loop is woken by an eventfd (a system call, not Qt's posted-event lock).
  std::atomic<ViewFrame*> m_pending{nullptr};
  std::atomic<Drawn*> m_drawn_frame{nullptr};
  std::atomic<bool> m_stop{false};
  std::atomic<long> m_drawn{0};
  int m_event_fd = -1;
  QSocketNotifier* m_notifier = nullptr;
  std::thread m_thread;
};

}  // namespace thaw::gui
