#include "src/gui/film_runner.h"

#include "src/gui/preview_renderer.h"
#include "src/pipeline/pipeline.h"

namespace thaw::gui {
namespace fs = std::filesystem;

FilmRunner::FilmRunner(QObject* parent) : QObject(parent) {}

FilmRunner::~FilmRunner() {
  if (m_thread.joinable()) m_thread.join();  // no cancel: the run finishes its stages
}

bool FilmRunner::start(const pipeline::RunScenario& scenario, const std::string& text,
                       const fs::path& dir) {
  if (m_running) return false;
  if (m_thread.joinable()) m_thread.join();
  m_running = true;
  m_dir = dir;
  m_thread = std::thread([this, scenario, text, dir] {
    lower_thread_priority();
    try {
      pipeline::RunOptions options;
      options.out_dir = dir;
      options.quiet = true;
      options.scenario_text = text;
      const pipeline::RunReport report = pipeline::run_pipeline(scenario, options);
      m_running = false;
      emit finished(QString::fromStdString(report.film.string()));
    } catch (const std::exception& e) {
      m_running = false;
      emit failed(QString::fromStdString(e.what()));
    }
  });
  return true;
}

int FilmRunner::frames_done() const {
  int n = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(m_dir / "frames", ec))
    n += entry.path().extension() == ".png";
  return n;
}

}  // namespace thaw::gui
