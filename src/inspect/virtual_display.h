#pragma once
// An X display for VTK's off-screen rendering. Debian's VTK 9.1 is built for X only (no EGL, no
// OSMesa) and aborts without a usable display, so rendering code holds a DisplayLease: if
// $DISPLAY opens, it is used; otherwise a private Xvfb server (Debian package xvfb, the server
// behind xvfb-run) is started on a free display number (-displayfd) and stopped when the last
// lease ends. Mesh checks never take a lease: they need no X. Knows nothing about VTK.
#include <string>

namespace thaw::inspect {

class DisplayLease {
 public:
  /// Throws thaw::UserError when there is no usable $DISPLAY and Xvfb cannot be found or started.
  /// `purpose` names what needs the display (e.g. "--screenshot") in that message.
  explicit DisplayLease(const std::string& purpose);
  DisplayLease(const DisplayLease&) = delete;
  DisplayLease& operator=(const DisplayLease&) = delete;
  ~DisplayLease();

  /// The display in use, e.g. ":0" or ":99".
  const std::string& display() const { return m_display; }
  /// True when this process started an Xvfb server for it.
  bool virtual_server() const { return m_virtual; }

 private:
  std::string m_display;
  bool m_virtual = false;
};

/// True when $DISPLAY is set and an X connection to it opens.
bool display_available();

/// True when a DisplayLease can be had: a usable $DISPLAY or Xvfb on PATH (so a caller such as
/// `thaw run` can skip pictures with a note instead of failing).
bool rendering_possible();

}  // namespace thaw::inspect
