#include "src/inspect/vtk_messages.h"

#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>

#include <mutex>

#include "base/error.h"

namespace thaw::inspect {
namespace {

std::mutex g_mutex;
int g_collectors = 0;
std::string g_first;  // the first message of the collecting scope: the cause

/// Keeps the reason of the first message of an active collector; prints nothing.
class ThawOutputWindow : public vtkOutputWindow {
 public:
  static ThawOutputWindow* New();
  vtkTypeMacro(ThawOutputWindow, vtkOutputWindow);
  void DisplayText(const char* text) override {
    if (text == nullptr) return;
    std::lock_guard<std::mutex> lock(g_mutex);
    if (g_collectors == 0 || !g_first.empty()) return;
    g_first = escape_control_characters(reason(text));
  }

 private:
  // "Algorithm X returned failure for request: ..." only says that an earlier step failed: not a
  // cause to show (thaw's own message says what failed).
  static bool is_consequence(const std::string& line) {
    return line.find("returned failure for request") != std::string::npos;
  }

  // Object addresses ("(0x55ce003f16a0)") differ from run to run and mean nothing to a user.
  static std::string without_addresses(std::string line) {
    for (std::size_t at = line.find("(0x"); at != std::string::npos; at = line.find("(0x", at)) {
      const std::size_t close = line.find(')', at);
      if (close == std::string::npos) break;
      std::size_t begin = at;
      if (begin > 0 && line[begin - 1] == ' ') --begin;
      line.erase(begin, close + 1 - begin);
      at = begin;
    }
    return line;
  }

  // The reason in a VTK message: "ERROR: In <source>, line N\n<Class> (0x...): <reason>\n..."
  // (further lines dump the pipeline's request, noise to a user) gives "<reason>".
  static std::string reason(const std::string& text) {
    std::size_t begin = 0;
    while (begin < text.size()) {
      std::size_t end = text.find('\n', begin);
      if (end == std::string::npos) end = text.size();
      std::string line = text.substr(begin, end - begin);
      begin = end + 1;
      while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
      if (line.empty() || line.rfind("ERROR: In ", 0) == 0 || line.rfind("Warning: In ", 0) == 0 ||
          line.rfind("Generic Warning: In ", 0) == 0)
        continue;
      const std::size_t object = line.find("): ");
      if (object != std::string::npos && line.find(" (0x") < object) line.erase(0, object + 3);
      return is_consequence(line) ? "" : without_addresses(line);
    }
    return "";
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
  if (g_collectors++ == 0) g_first.clear();
}

VtkMessages::~VtkMessages() {
  std::lock_guard<std::mutex> lock(g_mutex);
  --g_collectors;
}

std::string VtkMessages::suffix() const {
  std::lock_guard<std::mutex> lock(g_mutex);
  return g_first.empty() ? "" : "; VTK: " + g_first;
}

}  // namespace thaw::inspect
