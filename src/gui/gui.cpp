#include "src/gui/gui.h"

#include <QApplication>
#include <QTimer>

#include <cstdlib>
#include <memory>
#include <optional>

#include "base/error.h"
#include "base/interrupt.h"
#include "src/gui/film_runner.h"
#include "src/gui/main_window.h"
#include "src/gui/opengl_preload.h"
#include "src/gui/screenshot.h"
#include "src/inspect/virtual_display.h"

namespace thaw::gui {

int run_gui(const GuiOptions& options) {
  if (!options.tab.empty() && !is_tab_title(options.tab))
    throw UserError("", "--tab",
                    "no tab '" + options.tab + "' (render, scenario, simulation, scene)");
  ScenarioDocument document =
      options.scenario.empty() ? ScenarioDocument() : ScenarioDocument::load(options.scenario);
  // --screenshot is a batch run: a scenario that breaks a rule is its one-line error, exit 2, no
  // picture (as for `thaw run`); the interactive window opens it to be fixed.
  if (!options.screenshot.empty())
    if (const ScenarioCheck c = document.check(); !c.ok()) c.failure.rethrow();
  // Qt's xcb platform needs an X display; --screenshot may start a private Xvfb for it (as
  // `thaw inspect --screenshot` does). The offscreen platform needs none.
  const char* platform = std::getenv("QT_QPA_PLATFORM");
  const bool offscreen = platform && std::string(platform) == "offscreen";
  std::unique_ptr<inspect::DisplayLease> display;
  if (!offscreen && !inspect::display_available()) {
    if (options.screenshot.empty())
      throw UserError("", "gui",
                      "no X display: run it on a desktop, or with --screenshot under xvfb-run");
    display = std::make_unique<inspect::DisplayLease>("thaw gui --screenshot");
  }
  // The OpenGL driver loads on a thread of its own meanwhile (opengl_preload.h), not in show().
  std::optional<OpenGlPreload> opengl;
  if (!offscreen) opengl.emplace();
  static int argc = 1;
  static char name[] = "thaw";
  static char* argv[] = {name, nullptr};
  QApplication app(argc, argv);
  MainWindow window(std::move(document));
  if (!options.tab.empty()) window.select_tab(options.tab);
  if (opengl) opengl->wait();
  window.show();
  if (options.simulate) {
    if (!window.start_simulation())
      throw UserError(window.document().source_name(), "--simulate",
                      "the scenario has a problem: " + window.check().message);
    QObject::connect(&window, &MainWindow::simulationFinished, &window, [&window] {
      window.show_step(static_cast<int>(window.simulation_run()->steps.size() / 2));
    });
  }
  // Ctrl-C or SIGTERM (base/interrupt.h only raises a flag) closes the window; the
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
