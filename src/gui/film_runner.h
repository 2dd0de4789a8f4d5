#pragma once
// "Render film": `thaw run` itself (src/pipeline/pipeline.h: simulate, mesh, render, film,
// inspect, resumable) on the window's scenario into a chosen folder, on a background thread.
// Progress is the count of finished frames in DIR/frames (the pipeline has no callback). Cancel
// uses the pipeline's own interrupt (base/interrupt.h, as Ctrl-C on `thaw run`): the run
// stops at its next safe point (between simulation outputs, meshes, frames and tiles; ffmpeg is
// stopped), unwinding removes its temporary files, so nothing is half-written, and a rerun into
// the same folder resumes. That interrupt is process-wide: while it is set, other renders in the
// process skip their tiles too, so the preview redoes a pass that overlapped a cancel
// (interrupts_started()) and the simulation panel remeshes. Afterwards the window steps through
// or plays DIR/frames.
#include <QObject>
#include <QString>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <thread>

#include "src/pipeline/run_scenario.h"

namespace thaw::gui {

class FilmRunner : public QObject {
  Q_OBJECT
 public:
  explicit FilmRunner(QObject* parent = nullptr);
  /// Cancels a run in flight and waits for it to stop.
  ~FilmRunner() override;
  /// Starts `thaw run` of `scenario` (whose file text is `text`) into `dir`; false if running.
  bool start(const pipeline::RunScenario& scenario, const std::string& text,
             const std::filesystem::path& dir);
  /// Asks the run to stop at its next safe point (GUI thread; returns at once); `cancelled`
  /// follows. No-op when not running.
  void cancel();
  bool running() const { return m_running; }
  /// Frames rendered so far in the folder of the current (or last) run.
  int frames_done() const;

  /// How many film cancels have raised the process-wide interrupt so far: a render that
  /// overlapped one (the count changed, or interrupt_requested()) may have skipped tiles.
  static std::uint64_t interrupts_started();
  /// True while a film cancel's interrupt is raised (not a Ctrl-C of the process).
  static bool cancelling();

 signals:
  /// The run finished: the film's path ("" when ffmpeg could not encode it is an error).
  void finished(const QString& film);
  /// The run stopped at a safe point after cancel(); the folder holds no partial file.
  void cancelled();
  void failed(const QString& message);

 private:
  std::thread m_thread;
  std::atomic<bool> m_running{false}, m_cancel{false};
  std::filesystem::path m_dir;
};

}  // namespace thaw::gui
