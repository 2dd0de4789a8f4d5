#include "src/gui/film_runner.h"

#include "base/interrupt.h"
#include "src/gui/preview_renderer.h"
#include "src/pipeline/pipeline.h"

namespace thaw::gui {
namespace fs = std::filesystem;
namespace {

std::atomic<std::uint64_t> g_interrupts{0};
std::atomic<bool> g_cancelling{false};

/// Lowers a film cancel's interrupt once the run has stopped (or ended before it saw it).
void lower_interrupt() {
  clear_interrupt_request();
  g_cancelling = false;
}

}  // namespace

FilmRunner::FilmRunner(QObject* parent) : QObject(parent) {}

FilmRunner::~FilmRunner() {
  cancel();
  if (m_thread.joinable()) m_thread.join();
}

std::uint64_t FilmRunner::interrupts_started() {
  return g_interrupts.load();
}

bool FilmRunner::cancelling() {
  return g_cancelling.load();
}

bool FilmRunner::start(const pipeline::RunScenario& scenario, const std::string& text,
                       const fs::path& dir) {
  if (m_running) return false;
  if (m_thread.joinable()) m_thread.join();
  m_running = true;
  m_cancel = false;
  m_dir = dir;
  m_thread = std::thread([this, scenario, text, dir] {
    lower_thread_priority(kBackgroundNice);
    try {
      pipeline::RunOptions options;
      options.out_dir = dir;
      options.quiet = true;
      options.scenario_text = text;
      const pipeline::RunReport report = pipeline::run_pipeline(scenario, options);
      if (m_cancel) lower_interrupt();  // cancelled after the last safe point: it finished
      m_running = false;
      emit finished(QString::fromStdString(report.film.string()));
    } catch (const Interrupted&) {
      // Every stage has unwound (its temporaries removed): lower the interrupt for the rest of
      // the process.
      lower_interrupt();
      m_running = false;
      emit cancelled();
    } catch (const std::exception& e) {
      if (m_cancel) lower_interrupt();
      m_running = false;
      emit failed(QString::fromStdString(e.what()));
    }
  });
  return true;
}

void FilmRunner::cancel() {
  if (!m_running || m_cancel.exchange(true)) return;
  g_cancelling = true;
  ++g_interrupts;
  request_interrupt();  // as SIGINT would: the pipeline throws Interrupted at a safe point
}

int FilmRunner::frames_done() const {
  int n = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(m_dir / "frames", ec))
    n += entry.path().extension() == ".png";
  return n;
}

}  // namespace thaw::gui
