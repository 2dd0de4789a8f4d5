#pragma once
// `thaw gui [SCENARIO.toml]`: the interactive workbench (src/gui, the only place that includes
// Qt). This header is Qt-free so that src/cli stays Qt-free.
#include <filesystem>
#include <string>

namespace thaw::gui {

struct GuiOptions {
  /// the scenario to open ("" = the built-in default)
  std::filesystem::path scenario;
  /// --screenshot: lay out the window, render the preview and the 3D view, save the window as
  /// this PNG and exit ("" = interactive)
  std::filesystem::path screenshot;
  /// the tab shown first: "render", "scenario", "simulation" or "scene" ("" = render)
  std::string tab;
  /// start the simulation at once; --screenshot then waits for it and shows its middle step
  bool simulate = false;
};

/// Runs the window until it is closed; returns the exit code. Throws thaw::UserError when the
/// scenario cannot be read or no display can be had.
int run_gui(const GuiOptions& options);

}  // namespace thaw::gui
