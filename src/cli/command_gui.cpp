// thaw gui [SCENARIO.toml] [--screenshot PATH]: argument parsing only (src/gui does the work).
#include <filesystem>
#include <string>
#include <system_error>

#include "base/error.h"
#include "base/output_file.h"
#include "src/cli/commands.h"
#ifdef THAW_WITH_GUI
#include "src/gui/gui.h"
#endif

namespace thaw::cli {

namespace {
/// Before Qt starts: a .png in a folder that exists (the window is saved as PNG only).
void check_screenshot_path(const std::filesystem::path& path) {
  check_output_file(path, {".png"});
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : ".";
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw UserError(path.string(), "--screenshot", "folder '" + dir.string() + "' does not exist");
}
}  // namespace

void register_gui(CLI::App& app) {
  struct Args {
    std::string scenario, screenshot, tab;
    bool simulate = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = app.add_subcommand(
      "gui",
      "The interactive workbench: edit a scenario and its scene, preview the frame, run "
      "the simulation and scrub through its meshes (Qt + VTK; docs/gui.md).");
  sub->add_option("scenario", args->scenario, "scenario TOML (default: the built-in default)");
  sub->add_option(
      "--screenshot", args->screenshot,
      "load, lay out, render the preview and the 3D view, save the window as PNG, exit");
  sub->add_option("--tab", args->tab, "tab shown first: render, scenario, simulation or scene");
  sub->add_flag(
      "--simulate", args->simulate,
      "start the simulation at once (--screenshot waits for it and shows its middle step)");
  sub->callback([args] {
    if (!args->screenshot.empty()) check_screenshot_path(args->screenshot);
#ifdef THAW_WITH_GUI
    gui::GuiOptions options;
    options.scenario = args->scenario;
    options.screenshot = args->screenshot;
    options.tab = args->tab;
    options.simulate = args->simulate;
    const int code = gui::run_gui(options);
    if (code != 0) throw CLI::RuntimeError(code);
#else
    throw UserError("", "gui",
                    "this thaw was built without Qt (install qtbase5-dev libvtk9-qt-dev, "
                    "bash scripts/setup, and rebuild)");
#endif
  });
}

}  // namespace thaw::cli
