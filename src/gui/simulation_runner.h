#pragma once
// The Simulation panel's background run: the scenario's simulation sampled at the film's frame
// times (as `thaw run` samples it), written to a private work folder, meshed there (src/mesh:
// inner and outer surface per step), and every step's meshes loaded into memory so that the time
// slider shows any step at once. Runs on its own thread; progress and the result reach the GUI
// thread by queued signals. Cancel stops the solver at its next output time (the progress
// callback throws); the mesher, whose OpenMP loop cannot be left early, finishes its pass first.
#include <QObject>
#include <QString>
#include <QTemporaryDir>
#include <array>
#include <atomic>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "src/gui/shell_step.h"
#include "src/mesh/mesh_series.h"

namespace thaw::gui {

/// A finished run: one ShellStep per frame time reached.
struct SimulationRun {
  std::vector<sim::InterfaceRecord> rows;
  std::vector<std::shared_ptr<const ShellStep>> steps;
  /// the sections the run was made from (a run is stale once they change)
  std::string simulation_text, mesh_text;
  double simulate_seconds = 0, mesh_seconds = 0, load_seconds = 0;
  /// Flow runs: per output time {time [s], largest speed in the water [m/s], Rayleigh number},
  /// summary.json's "flow" rows (sim::SimulationResult::flow_records); empty without flow.
  std::vector<std::array<double, 3>> flow_records;
};

class SimulationRunner : public QObject {
  Q_OBJECT
 public:
  explicit SimulationRunner(QObject* parent = nullptr);
  ~SimulationRunner() override;

  /// Starts a run of `scenario` (GUI thread; returns at once). False if one is running.
  bool start(const pipeline::RunScenario& scenario);
  /// Asks the running run to stop (GUI thread; returns at once).
  void cancel();
  bool running() const { return m_running; }
  /// The last finished run (null before one finished).
  std::shared_ptr<const SimulationRun> result() const;

 signals:
  /// stage: "simulate", "mesh" or "load"; done of total items.
  void progress(const QString& stage, qint64 done, qint64 total);
  void finished();
  void cancelled();
  void failed(const QString& message);

 private:
  void run(pipeline::RunScenario scenario);
  /// Meshes every step of `simdir` (src/mesh); a process-wide interrupt that is not this run's
  /// cancel (a film's cancel) makes it mesh again.
  mesh::MeshManifest mesh_cancellably(const std::filesystem::path& simdir,
                                      const mesh::MeshOptions& options);

  QTemporaryDir m_work;
  std::thread m_thread;
  std::atomic<bool> m_running{false}, m_cancel{false};
  mutable std::mutex m_mutex;
  std::shared_ptr<const SimulationRun> m_result;
};

}  // namespace thaw::gui
