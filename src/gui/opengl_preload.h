#pragma once
// Loads the OpenGL driver on a thread of its own while the window is being built, so that the
// window's show() does not load it on the GUI thread. The first native window Qt's xcb platform
// creates asks GLX for its extensions, which makes GLX load its vendor library and Mesa's DRI
// driver (with LLVM, for llvmpipe): 30-35 ms of dynamic linking on the GUI thread inside show()
// (docs/benchmarks.md, "thaw gui"). The thread asks the same of a display connection of its
// own; the libraries then stay loaded (the connection stays open until the preload ends) and
// Qt's request finds them. Knows nothing of thaw; without a display it does nothing.
#include <thread>

namespace thaw::gui {

class OpenGlPreload {
 public:
  /// Starts the thread (nothing when $DISPLAY cannot be opened).
  OpenGlPreload();
  /// Waits for the thread: call it before the window's show(), so that Qt's first use of GLX
  /// never runs alongside the thread's.
  void wait();
  /// Waits, then closes the thread's display connection.
  ~OpenGlPreload();
  OpenGlPreload(const OpenGlPreload&) = delete;
  OpenGlPreload& operator=(const OpenGlPreload&) = delete;

 private:
  std::thread m_thread;
  void* m_display = nullptr;  // the thread's X display (Display*)
};

}  // namespace thaw::gui
