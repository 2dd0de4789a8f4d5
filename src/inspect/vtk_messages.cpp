#include "src/inspect/vtk_messages.h"

#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>

#include <mutex>

#include "src/common/error.h"

namespace thaw::inspect {
namespace {

std::mutex g_mutex;
int g_collectors = 0;
std::string g_last;

/// Keeps the last message of an active collector; prints nothing.
class ThawOutputWindow : public vtkOutputWindow {
 public:
  static ThawOutputWindow* New();
  vtkTypeMacro(ThawOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override {
    if (text == nullptr) return;
    std::lock_guard<std::mutex> lock(g_mutex);
    if (g_collectors == 0) return;
    std::string line = text;
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r' || line.back() == ' '))
      line.pop_back();
    g_last = escape_control_characters(line);
  }
};
vtkStandardNewMacro(ThawOutputWindow);

}  // namespace

void silence_vtk_output() {
  static std::once_flag once;
  std::call_once(once, [] {
    vtkSmartPointer<ThawOutputWindow> window = vtkSmartPointer<ThawOutputWindow>::New();
    vtkOutputWindow::SetInstance(window);
    // VTK 9 also logs errors through vtkLogger (loguru "ERR|" lines) straight to stderr.
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  });
}

VtkMessages::VtkMessages() {
  silence_vtk_output();
  std::lock_guard<std::mutex> lock(g_mutex);
  if (g_collectors++ == 0) g_last.clear();
}

VtkMessages::~VtkMessages() {
  std::lock_guard<std::mutex> lock(g_mutex);
  --g_collectors;
}

std::string VtkMessages::suffix() const {
  std::lock_guard<std::mutex> lock(g_mutex);
  return g_last.empty() ? "" : "; VTK: " + g_last;
}

}  // namespace thaw::inspect
