#include "src/gui/opengl_preload.h"

#include <GL/glx.h>
#include <X11/Xlib.h>

namespace thaw::gui {

OpenGlPreload::OpenGlPreload() {
  m_thread = std::thread([this] {
    Display* display = XOpenDisplay(nullptr);  // its own connection: never shared with Qt's
    m_display = display;
    if (display == nullptr) return;
    // What Qt's xcb platform asks first (QXcbWindow::create): GLX loads the screen's vendor
    // library and its DRI driver to answer.
    (void)glXQueryExtensionsString(display, DefaultScreen(display));
  });
}

void OpenGlPreload::wait() {
  if (m_thread.joinable()) m_thread.join();
}

OpenGlPreload::~OpenGlPreload() {
  wait();
  if (m_display != nullptr) XCloseDisplay(static_cast<Display*>(m_display));
}

}  // namespace thaw::gui
