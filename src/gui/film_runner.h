#pragma once
// "Render film": `thaw run` itself (src/pipeline/pipeline.h: simulate, mesh, render, film,
// inspect, resumable) on the window's scenario into a chosen folder, on a background thread.
// Progress is the count of finished frames in DIR/frames (the pipeline has no callback); there
// is no cancel (the pipeline stops only on SIGINT; a rerun resumes where it stopped). Afterwards
// the window steps through or plays DIR/frames.
#include <QObject>
#include <QString>
#include <atomic>
#include <filesystem>
#include <thread>

#include "src/pipeline/run_scenario.h"

namespace thaw::gui {

class FilmRunner : public QObject {
  Q_OBJECT
 public:
  explicit FilmRunner(QObject* parent = nullptr);
  ~FilmRunner() override;
  /// Starts `thaw run` of `scenario` (whose file text is `text`) into `dir`; false if running.
  bool start(const pipeline::RunScenario& scenario, const std::string& text,
             const std::filesystem::path& dir);
  bool running() const { return m_running; }
  /// Frames rendered so far in the folder of the current (or last) run.
  int frames_done() const;

 signals:
  /// The run finished: the film's path ("" when ffmpeg could not encode it is an error).
  void finished(const QString& film);
  void failed(const QString& message);

 private:
  std::thread m_thread;
  std::atomic<bool> m_running{false};
  std::filesystem::path m_dir;
};

}  // namespace thaw::gui
