#pragma once
// `thaw gui --screenshot PATH`: once the window is laid out, the preview's last pass is shown and
// the 3D view holds the shell, the whole window is grabbed (the VTK view included) and written as
// PNG. Used by the tests and docs/gui.md.
#include <filesystem>
#include <functional>
#include <string>

namespace thaw::gui {

class MainWindow;

/// Waits (on the event loop, never blocking it) for the preview and the 3D view, saves the window
/// to `png` and calls `done("")`, or `done(problem)` when that fails or takes over `timeout_s`.
void take_screenshot_when_ready(MainWindow& window, const std::filesystem::path& png,
                                std::function<void(const std::string&)> done,
                                double timeout_s = 300);

}  // namespace thaw::gui
