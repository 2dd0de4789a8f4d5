#include "src/gui/simulation_runner.h"

#include <chrono>

#include "base/atomic_file.h"
#include "base/error.h"
#include "base/interrupt.h"
#include "sim/format/simulation_output.h"
#include "sim/simulate.h"
#include "src/gui/preview_renderer.h"
#include "src/mesh/mesh_series.h"

namespace thaw::gui {
namespace fs = std::filesystem;
namespace {

/// Thrown from the solver's progress callback (sequential code) to stop a cancelled run.
struct Cancelled {};

double since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

SimulationRunner::SimulationRunner(QObject* parent) : QObject(parent) {}

SimulationRunner::~SimulationRunner() {
  m_cancel = true;
  if (m_thread.joinable()) m_thread.join();
}

bool SimulationRunner::start(const pipeline::RunScenario& scenario) {
  if (m_running) return false;
  if (m_thread.joinable()) m_thread.join();  // the previous run has ended
  m_cancel = false;
  m_running = true;
  m_thread = std::thread([this, scenario] { run(scenario); });
  return true;
}

void SimulationRunner::cancel() {
  m_cancel = true;
}

std::shared_ptr<const SimulationRun> SimulationRunner::result() const {
  std::lock_guard lock(m_mutex);
  return m_result;
}

mesh::MeshManifest SimulationRunner::mesh_cancellably(const std::filesystem::path& simdir,
                                                      const mesh::MeshOptions& options) {
  for (;;) {
    try {
      return mesh::mesh_simulation_folder(
          simdir, options,
          [this](std::int64_t done, std::int64_t total) { emit progress("mesh", done, total); });
    } catch (const Interrupted&) {
      // The process-wide interrupt: a film's cancel (film_runner.h) or Ctrl-C. The mesher stopped
      // cleanly; mesh again once it is lowered, unless this run is cancelled too.
      while (interrupt_requested() && !m_cancel)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      if (m_cancel) throw Cancelled{};
    }
  }
}

void SimulationRunner::run(pipeline::RunScenario sc) {
  lower_thread_priority(kBackgroundNice);
  try {
    if (!m_work.isValid()) throw UserError("", "", "no temporary folder for the simulation");
    auto run = std::make_shared<SimulationRun>();
    run->simulation_text = sc.simulation_text;
    run->mesh_text = sc.mesh_text;
    const fs::path simdir = fs::path(m_work.path().toStdString()) / "sim";
    // 1. simulate at the frame times, as thaw run does
    auto t = std::chrono::steady_clock::now();
    const sim::SimulationResult result = sim::simulate(
        sc.simulation, pipeline::frame_times(sc), [this](std::int64_t done, std::int64_t total) {
          if (m_cancel) throw Cancelled{};
          emit progress("simulate", done, total);
        });
    {
      StagingDirectory stage(simdir);
      sim::write_simulation_outputs(stage.path(), result);
      stage.commit();
    }
    run->simulate_seconds = since(t);
    if (m_cancel) throw Cancelled{};
    // 2. mesh every step (OpenMP inside; not interruptible)
    t = std::chrono::steady_clock::now();
    const mesh::MeshManifest manifest = mesh_cancellably(simdir, sc.mesh);
    run->mesh_seconds = since(t);
    if (m_cancel) throw Cancelled{};
    // 3. load every step's surfaces for the slider
    t = std::chrono::steady_clock::now();
    run->rows = result.interface_records();
    run->flow_records = result.flow_records;
    const fs::path mesh_dir = simdir / "mesh";
    const auto total = static_cast<qint64>(manifest.steps.size());
    for (const mesh::StepRecord& s : manifest.steps) {
      if (m_cancel) throw Cancelled{};
      sim::InterfaceRecord row = run->rows.at(static_cast<std::size_t>(s.step));
      std::optional<fs::path> outer, inner;
      if (s.outer.file) outer = mesh_dir / *s.outer.file;
      if (s.inner.file) inner = mesh_dir / *s.inner.file;
      run->steps.push_back(std::make_shared<const ShellStep>(read_shell_step(row, outer, inner)));
      emit progress("load", static_cast<qint64>(run->steps.size()), total);
    }
    run->load_seconds = since(t);
    {
      std::lock_guard lock(m_mutex);
      m_result = std::move(run);
    }
    m_running = false;
    emit finished();
  } catch (const Cancelled&) {
    m_running = false;
    emit cancelled();
  } catch (const std::exception& e) {
    m_running = false;
    emit failed(QString::fromStdString(e.what()));
  }
}

}  // namespace thaw::gui
