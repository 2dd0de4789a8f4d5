#pragma once
// The workbench window: the rendered preview (top left) and the 3D view of the shell (bottom
// left); tabs on the right for the render settings, the scenario and (later steps) the simulation
// and the scene. Every edit goes to the ScenarioDocument, which is re-parsed by the files' own
// parsers: a problem is shown under its field and blocks saving; a valid scenario restarts the
// progressive preview (PreviewRenderer, off the GUI thread).
#include <QImage>
#include <QMainWindow>
#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "src/gui/film_runner.h"
#include "src/gui/preview_renderer.h"
#include "src/gui/scenario_document.h"
#include "src/gui/simulation_runner.h"

class QLabel;
class QTabWidget;
class QAction;
class QComboBox;
class QPushButton;
class QProgressBar;
class QSlider;
class QTimer;
class QVBoxLayout;

namespace thaw::gui {

/// The window's tabs in order, by title (`--tab` takes one, case-insensitive).
inline constexpr std::array<const char*, 4> kTabTitles = {"Render", "Scenario", "Simulation",
                                                          "Scene"};
/// Whether `name` is one of kTabTitles, case-insensitive (checked before Qt starts, so a bad
/// --tab is one line).
bool is_tab_title(const std::string& name);

class KeyForm;
class ShellView;
class RadiusPlot;
class ScenePanel;

class MainWindow : public QMainWindow {
  Q_OBJECT
 public:
  explicit MainWindow(ScenarioDocument document, QWidget* parent = nullptr);
  ~MainWindow() override;

  /// Sets one key (as a field does) and re-checks; returns whether the scenario is valid now.
  bool apply_edit(const std::string& key, const TomlValue& value);
  /// Adds an opaque object of `shape` (sphere, box, plane; mesh with `mesh_file`) beside the
  /// shell, with the first material of the scene (a grey matte one is added if there is none);
  /// returns whether the scenario is valid afterwards.
  bool add_object(const std::string& shape, const std::string& mesh_file = "");
  /// Applies a structural change (adding or removing a table) and re-checks.
  void modify(const std::function<void(ScenarioDocument&)>& change);
  /// Puts `form` among the forms that show problems and values; with `connect_edits` its edits
  /// are applied as they come (the Scene tab's forms of the selected entry come and go).
  void register_form(KeyForm* form, bool connect_edits);
  void unregister_form(KeyForm* form);
  /// Removes [[render.objects]] entry `index`.
  bool remove_object(std::size_t index);
  /// Opens a scenario file; throws thaw::UserError if it is not TOML.
  void open_file(const std::filesystem::path& path);
  /// Saves to `path`; false (and the message shown) when the scenario has a problem.
  bool save_file(const std::filesystem::path& path);

  const ScenarioDocument& document() const { return m_document; }
  /// The last check's problem ("" when valid) and the key it names.
  const ScenarioCheck& check() const { return m_check; }
  /// Whether Save is enabled (the scenario is valid).
  bool can_save() const;
  /// The latest preview image and the pass it came from (-1 before the first).
  const QImage& preview_image() const { return m_image; }
  int preview_pass() const { return m_pass; }
  /// Whether the image shown is of the current request at its full size (the preview size, or
  /// the frame's size after Render): the first such image is what an edit waits for.
  bool preview_full_size() const { return m_pass >= 0 && m_image.size() == m_request_size; }
  /// The pass count of a full preview and the seconds from the edit to the latest image.
  int preview_passes() const { return m_passes; }
  double preview_seconds() const { return m_seconds; }
  PreviewRenderer& renderer() { return *m_renderer; }
  ShellView& shell_view() { return *m_view; }
  /// The inline message shown for `key` in whichever form has it ("" when none).
  QString field_problem(const std::string& key) const;
  // Render film
  /// Runs `thaw run` on the scenario into `dir` in the background; false if one is running or
  /// the scenario has a problem.
  bool start_film(const std::filesystem::path& dir);
  /// Stops the film's run at its next safe point (filmCancelled follows): nothing is left
  /// half-written, and start_film() into the same folder resumes.
  void cancel_film();
  bool film_running() const;
  /// The frames of the last finished film (sorted), shown by the frame slider.
  const std::vector<std::filesystem::path>& film_frames() const { return m_frames; }
  /// Shows film frame `index` in the preview area (the frame slider does this).
  void show_frame(int index);

  /// Shows the tab titled `name` (case-insensitive); false if there is none.
  bool select_tab(const std::string& name);
  /// Preview size (the Render tab's choice).
  void set_preview_size(int width, int height);

  // Simulation panel
  /// Starts the simulation of the current (valid) scenario in the background.
  bool start_simulation();
  void cancel_simulation();
  bool simulation_running() const;
  /// The finished run the slider scrubs (null before one, or once an edit made it stale).
  std::shared_ptr<const SimulationRun> simulation_run() const { return m_run; }
  /// Shows step `index` of the run in the 3D view, the plot and the preview (as the slider does).
  void show_step(int index);

 signals:
  /// Pass `pass` of the preview of the current scenario is shown (older requests' are dropped).
  void previewShown(int pass);
  /// The preview's last pass for the current scenario is shown.
  void previewFinished();
  void simulationFinished();
  void simulationCancelled();
  void filmFinished();
  void filmCancelled();

 private:
  QWidget* make_render_tab();
  /// The Render tab's rows: the frames' quality and the preview's size; Render film.
  void add_quality_rows(QVBoxLayout* v);
  void add_film_rows(QVBoxLayout* v);
  void connect_film();
  /// A film's run ended: its frames are listed and the first one shown.
  void on_film_finished(const QString& film);
  QWidget* make_scenario_tab();
  /// The Scenario tab's rows of a grid scenario: the grid solver's keys and the [shape] bodies.
  KeyForm* make_shape_form();
  QWidget* make_simulation_tab();
  void recheck();
  /// Before `simulation.geometry` becomes `geometry`: between a 1D geometry and a grid one,
  /// replaces [shell] by [shape] (or back), carrying a hollow sphere over.
  void switch_solver_family(const std::string& geometry);
  /// Makes the table of `kind_key` (just edited) hold the keys its new kind uses (see there).
  void fit_keys_to_kind(const std::string& kind_key);
  /// Greys out the fields of keys the scenario does not read (its geometry, its boundary kind).
  void grey_out_unused(const pipeline::RunScenario& scenario);
  void request_preview(bool full_quality = false);
  void on_image(const QImage& image, int pass, int passes, double seconds, quint64 serial);
  void show_image();
  void on_shell_ready();
  /// Where the frames place `step`'s shell (pipeline::shell_offset) [m].
  std::array<double, 3> shell_offset_of(const ShellStep& step) const;
  /// Writes the 3D view's camera (after an orbit) as the scenario's [render.camera].
  void camera_from_view();
  /// Shows the run's largest speed in the water (flow runs; hidden otherwise).
  void show_flow_speed();
  void update_title();
  void resizeEvent(QResizeEvent* event) override;

  ScenarioDocument m_document;
  ScenarioCheck m_check;
  std::filesystem::path m_path;
  PreviewRenderer* m_renderer;
  ShellView* m_view = nullptr;
  QLabel* m_preview = nullptr;
  QLabel* m_status = nullptr;
  QLabel* m_problem = nullptr;
  QTabWidget* m_tabs = nullptr;
  QAction* m_save = nullptr;
  QAction* m_save_as = nullptr;
  std::vector<KeyForm*> m_forms;
  /// the Scenario tab's 1D shell rows and grid [shape] rows: one of them is shown
  KeyForm* m_shell_form = nullptr;
  KeyForm* m_shape_form = nullptr;
  QImage m_image;
  int m_pass = -1, m_passes = 0;
  /// the serial of the latest preview request: only its images are shown
  std::uint64_t m_request_serial = 0;
  double m_seconds = 0;
  int m_preview_width = 320, m_preview_height = 240;
  /// the size of the current request's images
  QSize m_request_size;
  bool m_full_quality = false;
  SimulationRunner* m_runner = nullptr;
  std::shared_ptr<const SimulationRun> m_run;
  int m_step = -1;
  RadiusPlot* m_plot = nullptr;
  QSlider* m_slider = nullptr;
  /// the slider's step time
  QLabel* m_time_label = nullptr;
  QProgressBar* m_sim_progress = nullptr;
  QPushButton* m_run_button = nullptr;
  QPushButton* m_cancel_button = nullptr;
  QLabel* m_sim_status = nullptr;
  /// flow runs: the largest speed in the water over the run and at the slider's step
  QLabel* m_speed_label = nullptr;
  /// While the slider moves, the preview of the step waits for it to rest (the 3D view follows
  /// at once, without the outer surface's edges): renders restarted at every tick would take
  /// the CPU from the GUI thread.
  QTimer* m_scrub_timer = nullptr;
  ScenePanel* m_scene = nullptr;
  FilmRunner* m_film = nullptr;
  std::vector<std::filesystem::path> m_frames;
  QSlider* m_frame_slider = nullptr;
  QLabel* m_frame_label = nullptr;
  QPushButton* m_film_button = nullptr;
  QPushButton* m_film_cancel = nullptr;
  QPushButton* m_play_button = nullptr;
  QProgressBar* m_film_progress = nullptr;
  QTimer* m_film_poll = nullptr;
  QTimer* m_play_timer = nullptr;
  QLabel* m_film_status = nullptr;
};

}  // namespace thaw::gui
