#include "src/gui/screenshot.h"

#include <QBuffer>
#include <QElapsedTimer>
#include <QTimer>
#include <memory>

#include "base/atomic_file.h"
#include "base/error.h"
#include "src/gui/main_window.h"
#include "src/gui/shell_view.h"

namespace thaw::gui {

void take_screenshot_when_ready(MainWindow& window, const std::filesystem::path& png,
                                std::function<void(const std::string&)> done, double timeout_s) {
  auto clock = std::make_shared<QElapsedTimer>();
  clock->start();
  auto* poll = new QTimer(&window);
  poll->setInterval(50);
  QObject::connect(poll, &QTimer::timeout, &window, [&window, png, done, clock, poll, timeout_s] {
    const bool preview_done = window.preview_pass() >= 0 &&
                              window.preview_pass() + 1 == window.preview_passes() &&
                              !window.renderer().busy();
    const bool invalid = !window.check().ok();
    if (window.simulation_running()) return;
    // the view's latest frame received, and drawn at rest (not quick: a slider move settles)
    const bool view_done = (window.renderer().initial_shell() != nullptr || invalid) &&
                           !window.shell_view().drawing() && !window.shell_view().quick();
    if (!(preview_done || invalid) || !view_done) {
      if (clock->elapsed() > timeout_s * 1000) {
        poll->stop();
        done("the preview did not finish within the time limit");
      }
      return;
    }
    poll->stop();
    // The window's widgets, the 3D view's last frame among them (a raster widget).
    const QPixmap shot = window.grab();
    QByteArray bytes;
    QBuffer buffer(&bytes);
    buffer.open(QIODevice::WriteOnly);
    if (!shot.save(&buffer, "PNG")) return done("the window could not be encoded as PNG");
    try {
      write_file_atomic(
          png, std::string_view(bytes.constData(), static_cast<std::size_t>(bytes.size())));
    } catch (const UserError& e) {
      return done(e.problem());
    }
    done("");
  });
  poll->start();
}

}  // namespace thaw::gui
