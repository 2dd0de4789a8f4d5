#include "src/gui/gui.h"

#include <sys/resource.h>
#include <vtkRenderWindow.h>
#include <QApplication>
#include <QTimer>

#include <cstdlib>
#include <memory>
#include <optional>

#include "src/common/error.h"
#include "src/common/interrupt.h"
#include "src/gui/film_runner.h"
#include "src/gui/main_window.h"
#include "src/gui/opengl_preload.h"
#include "src/gui/scene_props.h"
#include "src/gui/screenshot.h"
#include "src/gui/shader_warmup.h"
#include "src/gui/shell_view.h"
#include "src/inspect/virtual_display.h"

namespace thaw::gui {
namespace {

/// The --warm-shaders child: once the 3D view has drawn the initial shell and the scene with all
/// their looks, adds one small actor of every look an edit can bring (look_catalog), and once
/// those are drawn too, draws it quick (the looks of an orbit or a slider drag), then quits with 0.
void quit_when_warmed(MainWindow& window, QApplication& app) {
  auto* poll = new QTimer(&window);
  auto catalog_added = std::make_shared<bool>(false);
  QObject::connect(poll, &QTimer::timeout, &window, [&window, &app, poll, catalog_added] {
    ShellView& view = window.shell_view();
    if (!window.check().ok()) return poll->stop(), app.exit(3);  // the parent compiles them
    if (view.triangles() == 0 || view.scene_objects() == 0 || view.warming_up()) return;
    if (!*catalog_added) {
      *catalog_added = true;
      const ShellView::ViewCamera c = view.camera();
      render::CameraDescription camera;
      camera.position = c.position;
      camera.look_at = c.focal_point;
      camera.up = c.view_up;
      camera.vertical_fov_deg = c.vertical_fov_deg;
      view.add_catalog(look_catalog(camera));
      return;
    }
    poll->stop();
    view.set_quick(true);
    view.renderWindow()->Render();
    view.set_quick(false);
    app.exit(0);
  });
  poll->start(50);
}

}  // namespace

int run_gui(const GuiOptions& options) {
  ScenarioDocument document =
      options.scenario.empty() ? ScenarioDocument() : ScenarioDocument::load(options.scenario);
  if (options.warm_shaders) {
    ::unsetenv("DISPLAY");  // always a private Xvfb: nothing appears on the user's screen
    ::unsetenv("QT_QPA_PLATFORM");
    // Below the parent's GUI thread, which it must not keep from a core.
    (void)::setpriority(PRIO_PROCESS, 0, 5);
  }
  // Qt's xcb platform needs an X display; --screenshot may start a private Xvfb for it (as
  // `thaw inspect --screenshot` does). The offscreen platform needs none.
  const char* platform = std::getenv("QT_QPA_PLATFORM");
  const bool offscreen = platform && std::string(platform) == "offscreen";
  std::unique_ptr<inspect::DisplayLease> display;
  if (!offscreen && !inspect::display_available()) {
    if (options.screenshot.empty() && !options.warm_shaders)
      throw UserError("", "gui",
                      "no X display: run it on a desktop, or with --screenshot under xvfb-run");
    display = std::make_unique<inspect::DisplayLease>(
        options.warm_shaders ? "thaw gui --warm-shaders (the 3D view's shader warm-up)"
                             : "thaw gui --screenshot");
  }
  // The OpenGL driver loads on a thread of its own meanwhile (opengl_preload.h), not in show().
  std::optional<OpenGlPreload> opengl;
  if (!offscreen) opengl.emplace();
  static int argc = 1;
  static char name[] = "thaw";
  static char* argv[] = {name, nullptr};
  QApplication app(argc, argv);
  MainWindow window(std::move(document));
  if (!options.tab.empty() && !window.select_tab(options.tab))
    throw UserError("", "--tab",
                    "no tab '" + options.tab + "' (render, scenario, simulation, scene)");
  if (opengl) opengl->wait();
  window.show();
  if (options.warm_shaders) {
    quit_when_warmed(window, app);
    return app.exec();
  }
  warm_shaders_first(window.shell_view(), QCoreApplication::applicationFilePath(),
                     options.scenario);
  if (options.simulate) {
    if (!window.start_simulation())
      throw UserError(window.document().source_name(), "--simulate",
                      "the scenario has a problem: " + window.check().message);
    QObject::connect(&window, &MainWindow::simulationFinished, &window, [&window] {
      window.show_step(static_cast<int>(window.simulation_run()->steps.size() / 2));
    });
  }
  // Ctrl-C or SIGTERM (src/common/interrupt.h only raises a flag) closes the window; the
  // film's own cancel raises the same flag and is told apart (film_runner.h).
  QTimer interrupt_poll;
  QObject::connect(&interrupt_poll, &QTimer::timeout, &app, [&app] {
    if (interrupt_requested() && !FilmRunner::cancelling()) app.quit();
  });
  interrupt_poll.start(200);
  if (options.screenshot.empty()) return app.exec();
  std::string problem;
  take_screenshot_when_ready(window, options.screenshot, [&](const std::string& p) {
    problem = p;
    app.exit(p.empty() ? 0 : 2);
  });
  const int code = app.exec();
  if (!problem.empty()) throw UserError(options.screenshot.string(), "--screenshot", problem);
  return code;
}

}  // namespace thaw::gui
