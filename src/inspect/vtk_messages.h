#pragma once
// VTK's own messages (vtkOutputWindow: ERR/WARN lines with colours and source locations) never
// reach the terminal: while a VtkMessages object lives, they are collected, and suffix() gives the
// first message's reason (its source location and pipeline dump left out) as "; VTK: ..." for the
// thaw::UserError that reports the failure, so a failure is one short thaw line. Outside such a
// scope they are dropped. VTK-free header.
#include <string>

namespace thaw::inspect {

class VtkMessages {
 public:
  VtkMessages();  ///< installs thaw's output window (once per process) and starts collecting
  ~VtkMessages();
  VtkMessages(const VtkMessages&) = delete;
  VtkMessages& operator=(const VtkMessages&) = delete;

  /// "" if VTK reported nothing, else "; VTK: <the first error or warning's reason, one line>".
  std::string suffix() const;
};

/// Installs thaw's output window without collecting: VTK prints nothing from then on.
void silence_vtk_output();

}  // namespace thaw::inspect
