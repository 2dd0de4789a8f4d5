#pragma once
// The progressive preview, off the GUI thread: one worker thread takes the newest request (a
// scenario, optionally a simulated shell step, a quality), meshes the initial shell if needed
// (cached while the shell's keys do not change), then renders preview_passes() one after the
// other, handing each image to the GUI thread by a queued signal. A new request cancels the
// render in flight (RenderOptions::cancel: its remaining tiles are skipped) and restarts from the
// quick pass; the GUI thread only ever takes a mutex for a copy. After a request's first image it
// also makes what the 3D view draws of the frame's scene (scene_props.h; its actors are reused
// while the scene's geometry and colours do not change). Knows nothing of the widgets.
#include <QImage>
#include <QObject>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "render/image/image.h"
#include "src/gui/preview_scene.h"
#include "src/gui/scene_props.h"

namespace thaw::gui {

struct PreviewRequest {
  pipeline::RunScenario scenario;
  /// the simulated step to show; empty: the scenario's initial shell
  std::shared_ptr<const ShellStep> step;
  /// rows the built-in camera frames (empty: the step's own row)
  std::vector<sim::InterfaceRecord> camera_rows;
  int width = 320, height = 240, samples = 4;
};

/// Lowers the calling thread's scheduling priority to `nice`, so that the preview's renders, a
/// simulation run and a film leave the GUI thread (and the 3D view's render thread, at
/// kViewNice) the cores whenever it needs them: the preview at kPreviewNice, the long runs
/// (simulation, film) below it at kBackgroundNice.
void lower_thread_priority(int nice);
inline constexpr int kPreviewNice = 10, kBackgroundNice = 15;

/// The linear image as 8-bit sRGB, scaled by 2^exposure (as the PNG writer does).
QImage to_qimage(const render::Image& image, double exposure);

class PreviewRenderer : public QObject {
  Q_OBJECT
 public:
  explicit PreviewRenderer(QObject* parent = nullptr);
  ~PreviewRenderer() override;

  /// Replaces whatever is pending or rendering by `request` (GUI thread; returns at once).
  /// Returns its serial number, which its images carry.
  std::uint64_t request(PreviewRequest request);
  /// Stops the pass in flight at its next tile and drops the pending request (GUI thread; the
  /// time slider moves: the 3D view's draws then have the cores, and the preview of the step
  /// is requested once the slider rests).
  void cancel();
  /// Requests left unfinished because a newer one (or cancel()) replaced them: a pass abandoned
  /// while rendering, or the next pass not started (stale previews cancelled).
  std::uint64_t abandoned_passes() const { return m_abandoned; }
  /// The initial shell the worker last meshed (for the 3D view); null before the first.
  std::shared_ptr<const ShellStep> initial_shell() const;
  /// What the 3D view draws of the latest served request's scene (null before the first).
  std::shared_ptr<const SceneProps> scene_props() const;
  /// True while a request is pending or a pass is rendering.
  bool busy() const;

 signals:
  /// A pass finished: its image, its index among `passes`, the seconds since the request and
  /// the request's serial (an image queued just before a newer request is stale: drop it).
  void imageReady(const QImage& image, int pass, int passes, double seconds, quint64 serial);
  /// The initial shell of a new scenario was meshed (initial_shell() has it).
  void shellReady();
  /// scene_props() was made for request `serial` (after its first image).
  void sceneReady(quint64 serial);
  /// The request cannot be rendered (a scene problem build_scene found); one line.
  void failed(const QString& message);

 private:
  void loop();
  void serve(const PreviewRequest& request, std::chrono::steady_clock::time_point start,
             std::uint64_t serial);
  void update_scene_props(const render::SceneDescription& desc, const ShellStep& step,
                          std::uint64_t serial);

  mutable std::mutex m_mutex;
  std::condition_variable m_wake;
  std::optional<PreviewRequest> m_pending;
  std::chrono::steady_clock::time_point m_requested_at;
  bool m_quit = false, m_rendering = false;
  std::atomic<bool> m_cancel{false};
  std::uint64_t m_serial = 0;  // guarded by m_mutex
  std::atomic<std::uint64_t> m_abandoned{0};
  std::shared_ptr<const ShellStep> m_initial;
  std::string m_initial_key;
  std::shared_ptr<const SceneProps> m_props;  // guarded by m_mutex
  std::thread m_thread;
};

}  // namespace thaw::gui
