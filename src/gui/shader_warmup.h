#pragma once
// The 3D view's shaders compiled off the GUI thread on a machine's first run. With software
// OpenGL (Mesa llvmpipe) each new look of the view (shell_view.h, "warm-up") compiles its shaders
// on the GUI thread in its first draw: 10-50 ms of CPU with Mesa's on-disk shader cache filled,
// 100-150 ms each without it. So when the cache is not known to hold this thaw's looks, the window
// holds its new looks (ShellView::hold) while a child process, `thaw gui --warm-shaders`, draws
// the same window on a private Xvfb (the same driver and shader sources, so its cache entries are
// the parent's hits) and exits; then the view draws its looks in turns, loading them from the
// cache. The child failing, or not finishing in time, only means the view compiles them itself.
// Knows nothing of the window's contents: the child is the same program drawing the same window.
#include <QObject>
#include <QString>
#include <QStringList>
#include <filesystem>

class QProcess;
class QTimer;

namespace thaw::gui {

class ShellView;

/// One child process run asynchronously: `finished(ok)` is emitted once, when it exits (ok: exit
/// code 0), cannot be started, or after `timeout_ms` (then it is killed; ok false).
class ShaderWarmup : public QObject {
  Q_OBJECT
 public:
  ShaderWarmup(const QString& program, const QStringList& arguments, int timeout_ms,
               QObject* parent = nullptr);
  /// Kills a child still running.
  ~ShaderWarmup() override;
  bool running() const { return !m_done; }

 signals:
  void finished(bool ok);

 private:
  void finish(bool ok);
  QProcess* m_process = nullptr;
  QTimer* m_timeout = nullptr;
  bool m_done = false;
};

/// The child's time limit: it meshes the shell and renders a quick preview before it draws, which
/// takes 2 s on a quiet machine; at most this long the view shows only its background.
constexpr int kShaderWarmupTimeoutMs = 20000;

/// Unless Mesa's shader cache is disabled or already warmed for this `thaw_exe` (a stamp file in
/// the cache's folder, written when a warm-up succeeded), holds `view` and starts
/// `thaw_exe gui --warm-shaders [scenario]`; the view is released when it ends, whatever the
/// outcome. Returns the warm-up (a child of `view`), or nullptr when none was needed.
ShaderWarmup* warm_shaders_first(ShellView& view, const QString& thaw_exe,
                                 const std::filesystem::path& scenario);

}  // namespace thaw::gui
