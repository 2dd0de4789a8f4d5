#pragma once
// VTK's own messages (vtkOutputWindow: ERR/WARN lines with colours and source locations) never
// reach the terminal: while a VtkMessages object lives, they are collected, and suffix() gives the
// last error as "; VTK: ..." for the thaw::UserError that reports the failure, so a failure is
// one thaw line. Outside such a scope they are dropped. VTK-free header.
#include <string>

namespace thaw::inspect {

class VtkMessages {
 public:
  VtkMessages();  ///< installs thaw's output window (once per process) and starts collecting
  ~VtkMessages();
  VtkMessages(const VtkMessages&) = delete;
  VtkMessages& operator=(const VtkMessages&) = delete;

  /// "" if VTK reported nothing, else "; VTK: <last error or warning, one line>".
  std::string suffix() const;
};

/// Installs thaw's output window without collecting: VTK prints nothing from then on.
void silence_vtk_output();

}  // namespace thaw::inspect
