#include "src/gui/main_window.h"

#include <QAction>
#include <QComboBox>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QMenuBar>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSlider>
#include <QSplitter>
#include <QStatusBar>
#include <QTabWidget>
#include <QTimer>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <map>

#include "base/check.h"
#include "base/error.h"
#include "render/scene/caustic_keys.h"
#include "render/scene/image_keys.h"
#include "sim/grid/grid_rules.h"
#include "sim/scenario/materials_keys.h"
#include "src/gui/key_form.h"
#include "src/gui/key_row_field.h"
#include "src/gui/radius_plot.h"
#include "src/gui/scene_panel.h"
#include "src/gui/shell_view.h"
#include "src/pipeline/frame_scene.h"

namespace thaw::gui {
namespace {

using pipeline::RunScenario;

QWidget* scrolled(QWidget* inner) {
  auto* area = new QScrollArea;
  area->setWidget(inner);
  area->setWidgetResizable(true);
  area->setFrameShape(QFrame::NoFrame);
  return area;
}

TomlValue d(double v) {
  return TomlValue{v};
}
TomlValue i(long long v) {
  return TomlValue{v};
}

/// A field for the [render.image] key `name`, built from its row (render/scene/image_keys.h).
void add_image_key(KeyForm* form, std::string_view name) {
  const render::ImageKey* row = render::find_image_key(name);
  THAW_CHECK(row != nullptr, "the Render tab names an [image] key of the table");
  add_key_row(
      form, *row, "render.image.",
      +[](const RunScenario& s) -> const render::ImageSettings& { return s.scene.image; });
}

}  // namespace

MainWindow::MainWindow(ScenarioDocument document, QWidget* parent)
    : QMainWindow(parent), m_document(std::move(document)), m_renderer(new PreviewRenderer(this)) {
  qRegisterMetaType<thaw::gui::TomlValue>();
  auto* left = new QSplitter(Qt::Vertical);
  m_preview = new QLabel;
  m_preview->setObjectName("preview");
  m_preview->setAlignment(Qt::AlignCenter);
  m_preview->setMinimumSize(320, 240);
  m_preview->setStyleSheet("background: #1b1d22; color: #aab;");
  m_preview->setText("rendering...");
  m_view = new ShellView;
  m_view->setObjectName("shell_view");
  left->addWidget(m_preview);
  left->addWidget(m_view);
  // The rendered preview (the frame as the film shows it) gets the larger part; a smaller 3D
  // view is also fewer pixels for software OpenGL to draw.
  left->setStretchFactor(0, 3);
  left->setStretchFactor(1, 2);
  left->setSizes({450, 300});

  m_tabs = new QTabWidget;
  m_tabs->setObjectName("tabs");
  m_tabs->addTab(make_render_tab(), kTabTitles[0]);
  m_tabs->addTab(scrolled(make_scenario_tab()), kTabTitles[1]);
  m_tabs->addTab(make_simulation_tab(), kTabTitles[2]);
  m_scene = new ScenePanel(*this);
  m_tabs->addTab(scrolled(m_scene), kTabTitles[3]);
  auto* right = new QWidget;
  auto* rv = new QVBoxLayout(right);
  rv->setContentsMargins(0, 0, 0, 0);
  m_problem = new QLabel;
  m_problem->setObjectName("problem");
  m_problem->setWordWrap(true);
  m_problem->setStyleSheet("color: #c0392b; font-weight: bold;");
  m_problem->hide();
  rv->addWidget(m_problem);
  rv->addWidget(m_tabs);

  auto* split = new QSplitter(Qt::Horizontal);
  split->addWidget(left);
  split->addWidget(right);
  split->setStretchFactor(0, 3);
  split->setStretchFactor(1, 2);
  setCentralWidget(split);
  m_status = new QLabel;
  m_status->setObjectName("status");
  statusBar()->addWidget(m_status, 1);

  QMenu* file = menuBar()->addMenu("&File");
  QAction* open = file->addAction("&Open...", this, [this] {
    const QString p = QFileDialog::getOpenFileName(this, "Open scenario", {}, "Scenario (*.toml)");
    if (p.isEmpty()) return;
    try {
      open_file(p.toStdString());
    } catch (const UserError& e) {
      m_status->setText(QString::fromStdString(e.what()));
    }
  });
  open->setShortcut(QKeySequence::Open);
  m_save = file->addAction("&Save", this, [this] {
    if (m_path.empty()) return m_save_as->trigger();
    save_file(m_path);
  });
  m_save->setShortcut(QKeySequence::Save);
  m_save_as = file->addAction("Save &as...", this, [this] {
    const QString p = QFileDialog::getSaveFileName(this, "Save scenario", {}, "Scenario (*.toml)");
    if (!p.isEmpty()) save_file(p.toStdString());
  });
  file->addAction("&Quit", this, &QWidget::close)->setShortcut(QKeySequence::Quit);

  connect(m_view, &ShellView::cameraMoved, this, &MainWindow::camera_from_view);
  connect(m_renderer, &PreviewRenderer::imageReady, this, &MainWindow::on_image);
  connect(m_renderer, &PreviewRenderer::shellReady, this, &MainWindow::on_shell_ready);
  connect(m_renderer, &PreviewRenderer::sceneReady, this, [this](quint64 serial) {
    // Only the current request's: an older one's camera would undo an orbit just written back.
    if (serial != m_request_serial) return;
    if (auto props = m_renderer->scene_props(); props && props->serial == serial)
      m_view->set_scene(*props);
  });
  connect(m_renderer, &PreviewRenderer::failed, this, [this](const QString& message) {
    m_status->setText("preview: " + message);
    m_problem->setText(message);
    m_problem->show();
  });
  for (KeyForm* form : {m_forms[0], m_forms[1]})  // Render and Scenario tabs
    connect(form, &KeyForm::edited, this,
            [this](const std::string& key, const TomlValue& value) { apply_edit(key, value); });
  if (m_document.source_name() != "<built-in default>") m_path = m_document.source_name();
  resize(1280, 800);
  recheck();
}

// The worker thread is stopped (and joined) before the widgets its signals reach go away. The
// forms are silenced first: the children are deleted after the members (the document among
// them), and a field losing the focus then would apply its edit to a destroyed document.
MainWindow::~MainWindow() {
  for (KeyForm* form : findChildren<KeyForm*>()) form->blockSignals(true);
  delete m_renderer;
}

QWidget* MainWindow::make_render_tab() {
  auto* page = new QWidget;
  auto* v = new QVBoxLayout(page);
  add_quality_rows(v);
  add_film_rows(v);
  auto* note = new QLabel(
      "The preview renders the first film frame as <tt>thaw run</tt> would: a quick pass at the "
      "preview size, then with the frame's anti-aliasing and caustics. Every edit restarts it. "
      "The 3D view below shows the same scene through the same camera: orbit, pan or zoom it "
      "and the camera is written back.");
  note->setWordWrap(true);
  v->addWidget(note);
  v->addStretch(1);
  return page;
}

void MainWindow::add_quality_rows(QVBoxLayout* v) {
  auto* form = new KeyForm;
  form->add_section("Quality of the film's frames ([render.image])");
  for (std::string_view key : {"width", "height", "samples_per_pixel", "exposure"})
    add_image_key(form, key);
  add_key_row(
      form, *find_key(render::caustic_keys(), "enabled"), "render.caustics.",
      +[](const RunScenario& s) -> const render::CausticSettings& { return s.scene.caustics; });
  m_forms.push_back(form);
  v->addWidget(form);
  auto* row = new QHBoxLayout;
  row->addWidget(new QLabel("Preview width"));
  auto* size = new QComboBox;
  size->setObjectName("preview_size");
  size->addItems({"160", "320", "480", "640"});
  size->setCurrentText("320");
  connect(size, &QComboBox::currentTextChanged, this, [this](const QString& w) {
    m_preview_width = w.toInt();
    request_preview();
  });
  row->addWidget(size);
  auto* render = new QPushButton("Render");
  render->setObjectName("render_button");
  render->setToolTip("Render the frame at the quality above (in the background)");
  connect(render, &QPushButton::clicked, this, [this] { request_preview(true); });
  row->addWidget(render);
  v->addLayout(row);
}

// Render film: thaw run into a folder, then step through or play its frames here.
void MainWindow::add_film_rows(QVBoxLayout* v) {
  m_film = new FilmRunner(this);
  auto* frow = new QHBoxLayout;
  m_film_button = new QPushButton("Render film...");
  m_film_button->setObjectName("film_button");
  m_film_button->setToolTip(
      "thaw run on this scenario into a folder (simulate, mesh, render, film)");
  frow->addWidget(m_film_button);
  m_film_cancel = new QPushButton("Cancel");
  m_film_cancel->setObjectName("film_cancel_button");
  m_film_cancel->setToolTip(
      "Stop the run at its next safe point; nothing is left half-written, and Render film into "
      "the same folder resumes where it stopped");
  m_film_cancel->setEnabled(false);
  connect(m_film_cancel, &QPushButton::clicked, this, [this] { cancel_film(); });
  frow->addWidget(m_film_cancel);
  m_film_progress = new QProgressBar;
  m_film_progress->setObjectName("film_progress");
  m_film_progress->setRange(0, 1);
  m_film_progress->setValue(0);
  m_film_progress->setFormat("no film rendered yet");
  frow->addWidget(m_film_progress, 1);
  v->addLayout(frow);
  auto* prow = new QHBoxLayout;
  m_play_button = new QPushButton("Play");
  m_play_button->setEnabled(false);
  m_frame_slider = new QSlider(Qt::Horizontal);
  m_frame_slider->setObjectName("frame_slider");
  m_frame_slider->setEnabled(false);
  m_frame_label = new QLabel("frame -");
  m_frame_label->setObjectName("frame_label");
  prow->addWidget(m_play_button);
  prow->addWidget(m_frame_slider, 1);
  prow->addWidget(m_frame_label);
  v->addLayout(prow);
  m_film_status = new QLabel;
  m_film_status->setWordWrap(true);
  v->addWidget(m_film_status);
  connect_film();
}

void MainWindow::connect_film() {
  m_film_poll = new QTimer(this);
  m_film_poll->setInterval(300);
  connect(m_film_poll, &QTimer::timeout, this,
          [this] { m_film_progress->setValue(m_film->frames_done()); });
  m_play_timer = new QTimer(this);
  connect(m_play_timer, &QTimer::timeout, this, [this] {
    const int next = m_frame_slider->value() + 1;
    if (next > m_frame_slider->maximum()) return m_play_timer->stop();
    m_frame_slider->setValue(next);
  });
  connect(m_play_button, &QPushButton::clicked, this, [this] {
    if (m_frame_slider->value() == m_frame_slider->maximum()) m_frame_slider->setValue(0);
    const double fps = m_check.ok() ? m_check.scenario->film.fps : 12.0;
    m_play_timer->start(static_cast<int>(1000.0 / fps));
  });
  connect(m_frame_slider, &QSlider::valueChanged, this, [this](int k) { show_frame(k); });
  connect(m_film_button, &QPushButton::clicked, this, [this] {
    const QString dir =
        QFileDialog::getExistingDirectory(this, "Folder for the film (thaw run --out)");
    if (!dir.isEmpty()) start_film(dir.toStdString());
  });
  connect(m_film, &FilmRunner::finished, this, &MainWindow::on_film_finished);
  connect(m_film, &FilmRunner::failed, this, [this](const QString& message) {
    m_film_poll->stop();
    m_film_button->setEnabled(true);
    m_film_cancel->setEnabled(false);
    m_film_status->setText("Failed: " + message);
  });
  connect(m_film, &FilmRunner::cancelled, this, [this] {
    m_film_poll->stop();
    m_film_progress->setValue(m_film->frames_done());
    m_film_button->setEnabled(true);
    m_film_cancel->setEnabled(false);
    m_film_status->setText(QString("Cancelled after %1 frames; nothing is half-written. Render "
                                   "film into the same folder resumes.")
                               .arg(m_film->frames_done()));
    emit filmCancelled();
  });
}

void MainWindow::on_film_finished(const QString& film) {
  m_film_poll->stop();
  m_film_button->setEnabled(true);
  m_film_cancel->setEnabled(false);
  m_frames.clear();
  std::error_code ec;
  const std::filesystem::path frames =
      std::filesystem::path(film.toStdString()).parent_path() / "frames";
  for (const auto& e : std::filesystem::directory_iterator(frames, ec))
    if (e.path().extension() == ".png") m_frames.push_back(e.path());
  std::sort(m_frames.begin(), m_frames.end());
  m_film_progress->setValue(static_cast<int>(m_frames.size()));
  m_film_status->setText("Film: " + film + ". Step through the frames or play them.");
  m_frame_slider->setRange(0, std::max(0, static_cast<int>(m_frames.size()) - 1));
  m_frame_slider->setEnabled(!m_frames.empty());
  m_play_button->setEnabled(!m_frames.empty());
  show_frame(0);
  emit filmFinished();
}

QWidget* MainWindow::make_scenario_tab() {
  auto* page = new QWidget;
  auto* v = new QVBoxLayout(page);
  v->setContentsMargins(0, 0, 0, 0);
  v->setSpacing(0);
  auto* top = new KeyForm;
  top->add_section("Geometry and sizes");
  top->add_choice("Geometry", "simulation.geometry",
                  {"sphere", "cylinder", "planar", "axisymmetric", "3d"}, [](const RunScenario& s) {
                    return TomlValue{std::string(s.simulation.grid == sim::GridGeometry::none
                                                     ? sim::to_string(s.simulation.geometry)
                                                     : sim::to_string(s.simulation.grid))};
                  });
  m_forms.push_back(top);  // m_forms[1]: its edits are connected by the constructor
  v->addWidget(top);
  // The 1D shell's radii or the grid body's [shape]: only the geometry's own rows are shown.
  m_shell_form = new KeyForm;
  m_shell_form->setObjectName("shell_form");
  v->addWidget(m_shell_form);
  m_shape_form = make_shape_form();
  v->addWidget(m_shape_form);
  register_form(m_shell_form, true);
  register_form(m_shape_form, true);
  auto* form = new KeyForm;
  v->addWidget(form);
  register_form(form, true);
  m_shell_form->add_number("Inner radius [m]", "shell.inner_radius_m",
                           [](const RunScenario& s) { return d(s.simulation.inner_radius_m); });
  m_shell_form->add_number("Outer radius [m]", "shell.outer_radius_m",
                           [](const RunScenario& s) { return d(s.simulation.outer_radius_m); });
  m_shell_form->add_number("Cylinder length [m]", "shell.length_m",
                           [](const RunScenario& s) { return d(s.simulation.length_m); });
  m_shell_form->add_number("Slab lateral size [m]", "shell.lateral_size_m",
                           [](const RunScenario& s) { return d(s.simulation.lateral_size_m); });
  form->add_section("Temperatures");
  form->add_number("Water at t = 0 [C]", "water.initial_temperature_c", [](const RunScenario& s) {
    return d(s.simulation.water_initial_temperature_c);
  });
  form->add_number("Ice at t = 0 [C]", "ice.initial_temperature_c",
                   [](const RunScenario& s) { return d(s.simulation.ice_initial_temperature_c); });
  form->add_section("Outer boundary");
  form->add_choice("Kind", "outer_boundary.kind",
                   {"temperature", "convective", "flux", "insulated", "air"},
                   [](const RunScenario& s) {
                     return TomlValue{std::string(sim::to_string(s.simulation.outer_kind))};
                   });
  form->add_number("Temperature [C]", "outer_boundary.temperature_c",
                   [](const RunScenario& s) { return d(s.simulation.outer_temperature_c); });
  form->add_number(
      "h [W/(m2 K)]", "outer_boundary.heat_transfer_coefficient_w_m2k",
      [](const RunScenario& s) { return d(s.simulation.heat_transfer_coefficient_w_m2k); });
  form->add_number("Flux [W/m2]", "outer_boundary.flux_w_m2",
                   [](const RunScenario& s) { return d(s.simulation.flux_w_m2); });
  form->add_number("Air: relative humidity", "outer_boundary.relative_humidity",
                   [](const RunScenario& s) { return d(s.simulation.relative_humidity); });
  form->add_number("Air: speed [m/s]", "outer_boundary.speed_m_s",
                   [](const RunScenario& s) { return d(s.simulation.air_speed_m_s); });
  form->add_number("Air: surroundings [C]", "outer_boundary.surroundings_temperature_c",
                   [](const RunScenario& s) {
                     return d(s.simulation.surroundings_temperature_c.value_or(
                         s.simulation.outer_temperature_c));
                   });
  form->add_number("Air: emissivity", "outer_boundary.emissivity",
                   [](const RunScenario& s) { return d(s.simulation.emissivity); });
  form->add_section("Materials");
  // The properties by their rows (sim/scenario/materials_keys.h); the flowing water's keys are
  // edited in the file.
  for (const sim::MaterialsKey& row : sim::materials_keys())
    if (!row.extra.flow)
      add_key_row(
          form, row, "materials.",
          +[](const RunScenario& s) -> const sim::Materials& { return s.simulation.materials; });
  form->add_section("Duration and frames");
  form->add_number("Duration [s]", "simulation.duration_s",
                   [](const RunScenario& s) { return d(s.simulation.duration_s); });
  form->add_number("Output interval [s]", "simulation.output_interval_s",
                   [](const RunScenario& s) { return d(s.simulation.output_interval_s); });
  form->add_integer("Film frames", "film.frames",
                    [](const RunScenario& s) { return i(s.film.frames); });
  form->add_number("Frames per second", "film.fps",
                   [](const RunScenario& s) { return d(s.film.fps); });
  v->addStretch(1);
  return page;
}

namespace {

/// The rows of one body of [shape] (`table` = "shape.outer" or "shape.cavity"): its kind and the
/// keys of every kind (those of other kinds greyed out, grey_out_unused), as
/// sim/format/scenario_file.cpp reads them. The cavity's kind has "none": no cavity (solid ice).
void add_shape_rows(KeyForm* form, const std::string& table, bool cavity) {
  using sim::ShapeSpec;
  auto spec = [cavity](const RunScenario& s) -> const ShapeSpec* {
    if (!cavity) return &s.simulation.shape.outer;
    return s.simulation.shape.cavity ? &*s.simulation.shape.cavity : nullptr;
  };
  auto number = [spec](double ShapeSpec::*field) {
    return [spec, field](const RunScenario& s) {
      const ShapeSpec* p = spec(s);
      return d(p ? p->*field : 0.0);
    };
  };
  auto vector = [spec](std::array<double, 3> ShapeSpec::*field) {
    return [spec, field](const RunScenario& s) {
      const ShapeSpec* p = spec(s);
      return TomlValue{p ? p->*field : std::array<double, 3>{0, 0, 0}};
    };
  };
  QStringList kinds{"box", "sphere", "cylinder", "obj"};
  if (cavity) kinds.prepend("none");
  form->add_choice("Kind", table + ".kind", kinds, [spec](const RunScenario& s) {
    const ShapeSpec* p = spec(s);
    return TomlValue{std::string(p ? sim::to_string(p->kind) : "none")};
  });
  form->add_vector("Centre [m]", table + ".center_m", vector(&ShapeSpec::center_m));
  form->add_vector("Box size [m]", table + ".size_m", vector(&ShapeSpec::size_m));
  form->add_number("Box edge radius [m]", table + ".edge_radius_m",
                   number(&ShapeSpec::edge_radius_m));
  form->add_number("Radius [m]", table + ".radius_m", number(&ShapeSpec::radius_m));
  form->add_number("Cylinder height [m]", table + ".height_m", number(&ShapeSpec::height_m));
  form->add_number("OBJ scale", table + ".scale", number(&ShapeSpec::scale));
  form->add_vector("OBJ translation [m]", table + ".translate_m", vector(&ShapeSpec::translate_m));
}

}  // namespace

KeyForm* MainWindow::make_shape_form() {
  auto* form = new KeyForm;
  form->setObjectName("shape_form");
  form->add_section("Grid solver ([simulation])");
  form->add_number("Cell size [m]", "simulation.cell_size_m", [](const RunScenario& s) {
    // The effective cell: the scenario's, or the default the solver picks.
    try {
      return d(sim::effective_cell_size_m(s.simulation));
    } catch (const UserError&) {
      return d(s.simulation.cell_size_m);
    }
  });
  form->add_choice("Flow in the water", "simulation.flow", {"none", "natural_convection"},
                   [](const RunScenario& s) {
                     return TomlValue{std::string(
                         s.simulation.natural_convection ? "natural_convection" : "none")};
                   });
  form->add_number("Largest time step [s]", "simulation.max_step_s",
                   [](const RunScenario& s) { return d(s.simulation.max_step_s); });
  form->add_section("Body ([shape] outer)");
  add_shape_rows(form, "shape.outer", false);
  form->add_section("Cavity ([shape] cavity)");
  add_shape_rows(form, "shape.cavity", true);
  return form;
}

QWidget* MainWindow::make_simulation_tab() {
  m_runner = new SimulationRunner(this);
  auto* page = new QWidget;
  auto* v = new QVBoxLayout(page);
  auto* row = new QHBoxLayout;
  m_run_button = new QPushButton("Simulate");
  m_run_button->setObjectName("simulate_button");
  m_run_button->setToolTip("Simulate and mesh the scenario at the film's frame times (background)");
  m_cancel_button = new QPushButton("Cancel");
  m_cancel_button->setObjectName("cancel_button");
  m_cancel_button->setEnabled(false);
  row->addWidget(m_run_button);
  row->addWidget(m_cancel_button);
  v->addLayout(row);
  m_sim_progress = new QProgressBar;
  m_sim_progress->setObjectName("simulation_progress");
  m_sim_progress->setFormat("%p%");
  v->addWidget(m_sim_progress);
  m_sim_status = new QLabel("Not simulated yet: the views show the initial shell.");
  m_sim_status->setObjectName("simulation_status");
  m_sim_status->setWordWrap(true);
  v->addWidget(m_sim_status);
  m_speed_label = new QLabel;
  m_speed_label->setObjectName("flow_speed");
  m_speed_label->setWordWrap(true);
  m_speed_label->hide();
  v->addWidget(m_speed_label);
  m_plot = new RadiusPlot;
  m_plot->setObjectName("radius_plot");
  v->addWidget(m_plot, 1);
  auto* srow = new QHBoxLayout;
  srow->addWidget(new QLabel("Time"));
  m_slider = new QSlider(Qt::Horizontal);
  m_slider->setObjectName("time_slider");
  m_slider->setEnabled(false);
  srow->addWidget(m_slider, 1);
  m_time_label = new QLabel("-");
  m_time_label->setObjectName("time_label");
  m_time_label->setMinimumWidth(m_time_label->fontMetrics().horizontalAdvance("00.0 min"));
  m_time_label->setAlignment(Qt::AlignRight | Qt::AlignVCenter);
  srow->addWidget(m_time_label);
  v->addLayout(srow);
  connect(m_run_button, &QPushButton::clicked, this, [this] { start_simulation(); });
  connect(m_cancel_button, &QPushButton::clicked, this, [this] { cancel_simulation(); });
  m_scrub_timer = new QTimer(this);
  m_scrub_timer->setSingleShot(true);
  m_scrub_timer->setInterval(120);
  connect(m_scrub_timer, &QTimer::timeout, this, [this] {
    m_view->settle();
    request_preview();
  });
  connect(m_slider, &QSlider::valueChanged, this, [this](int k) { show_step(k); });
  connect(m_runner, &SimulationRunner::progress, this,
          [this](const QString& stage, qint64 done, qint64 total) {
            m_sim_progress->setMaximum(static_cast<int>(std::max<qint64>(1, total)));
            m_sim_progress->setValue(static_cast<int>(done));
            m_sim_progress->setFormat(stage + " %v/%m");
          });
  auto ended = [this](const QString& text) {
    m_run_button->setEnabled(true);
    m_cancel_button->setEnabled(false);
    m_sim_status->setText(text);
  };
  connect(m_runner, &SimulationRunner::finished, this, [this, ended] {
    m_run = m_runner->result();
    m_sim_progress->setFormat("done: %m steps");
    ended(QString("%1 steps: simulated in %2 s, meshed in %3 s, loaded in %4 s. Drag the slider.")
              .arg(m_run->steps.size())
              .arg(m_run->simulate_seconds, 0, 'f', 2)
              .arg(m_run->mesh_seconds, 0, 'f', 2)
              .arg(m_run->load_seconds, 0, 'f', 2));
    m_plot->set_rows(m_run->rows);
    show_flow_speed();
    m_slider->setRange(0, static_cast<int>(m_run->steps.size()) - 1);
    m_slider->setEnabled(!m_run->steps.empty());
    m_step = -1;
    if (m_slider->value() == 0)
      show_step(0);
    else
      m_slider->setValue(0);
    emit simulationFinished();
  });
  connect(m_runner, &SimulationRunner::cancelled, this, [this, ended] {
    ended("Cancelled.");
    emit simulationCancelled();
  });
  connect(m_runner, &SimulationRunner::failed, this,
          [ended](const QString& message) { ended("Failed: " + message); });
  return page;
}

bool MainWindow::start_simulation() {
  if (!m_check.ok() || m_runner->running()) return false;
  if (!m_runner->start(*m_check.scenario)) return false;
  m_run_button->setEnabled(false);
  m_cancel_button->setEnabled(true);
  m_sim_progress->setValue(0);
  m_sim_status->setText("Simulating...");
  return true;
}

void MainWindow::cancel_simulation() {
  m_runner->cancel();
  m_sim_status->setText("Cancelling...");
}

bool MainWindow::simulation_running() const {
  return m_runner->running();
}

void MainWindow::show_step(int index) {
  if (!m_run || index < 0 || index >= static_cast<int>(m_run->steps.size())) return;
  m_step = index;
  const ShellStep& step = *m_run->steps[static_cast<std::size_t>(index)];
  m_view->show_step(step, shell_offset_of(step), false, /*moving=*/true);
  m_plot->set_marker(step.row.time_s);
  m_time_label->setText(QString("%1 min").arg(step.row.time_s / 60.0, 0, 'f', 1));
  show_flow_speed();
  if (m_slider->value() != index) m_slider->setValue(index);
  m_pass = -1;  // the image shown is of another step now
  // The preview follows once the slider rests; meanwhile no pass takes the cores from the 3D
  // view's draws (at load, a pass in flight made every move slower than the rest interval).
  m_renderer->cancel();
  m_scrub_timer->start();
}

void MainWindow::show_flow_speed() {
  // summary.json's "flow" rows: the largest speed over the run, and at the slider's step.
  const bool flow = m_run && !m_run->flow_records.empty();
  m_speed_label->setVisible(flow);
  if (!flow) return;
  const auto largest = std::max_element(m_run->flow_records.begin(), m_run->flow_records.end(),
                                        [](const auto& a, const auto& b) { return a[1] < b[1]; });
  QString text = QString("Largest speed in the water: %1 mm/s (at %2 min)")
                     .arg((*largest)[1] * 1e3, 0, 'f', 2)
                     .arg((*largest)[0] / 60.0, 0, 'f', 1);
  if (m_step >= 0) {
    const double t = m_run->steps[static_cast<std::size_t>(m_step)]->row.time_s;
    for (const auto& f : m_run->flow_records)
      if (f[0] == t) text += QString("; at this step %1 mm/s").arg(f[1] * 1e3, 0, 'f', 2);
  }
  m_speed_label->setText(text + ".");
}

bool MainWindow::apply_edit(const std::string& key, const TomlValue& value) {
  const std::string* text = std::get_if<std::string>(&value);
  if (key == "shape.cavity.kind" && text && *text == "none") {  // solid ice: no cavity table
    m_document.remove("shape.cavity");
    recheck();
    return m_check.ok();
  }
  if (key == "simulation.geometry" && text) switch_solver_family(*text);
  m_document.set(key, value);
  if (key.size() > 5 && key.compare(key.size() - 5, 5, ".kind") == 0) fit_keys_to_kind(key);
  recheck();
  return m_check.ok();
}

bool MainWindow::add_object(const std::string& shape, const std::string& mesh_file) {
  std::vector<std::string> materials = m_document.table_keys("render.materials");
  if (materials.empty()) {
    m_document.set("render.materials.grey.kind", std::string("matte"));
    m_document.set("render.materials.grey.color", std::array<double, 3>{0.7, 0.7, 0.7});
    materials.push_back("grey");
  }
  const std::size_t k = m_document.append_table("render.objects");
  const std::string key = "render.objects[" + std::to_string(k) + "].";
  m_document.set(key + "shape", shape);
  // Placed beside the default shell (3 cm radius at the origin, resting on y = 0).
  if (shape == "sphere") {
    m_document.set(key + "center", std::array<double, 3>{0.07, 0.015, 0.0});
    m_document.set(key + "radius", 0.015);
  } else if (shape == "box") {
    m_document.set(key + "min", std::array<double, 3>{-0.09, 0.0, -0.03});
    m_document.set(key + "max", std::array<double, 3>{-0.06, 0.03, 0.0});
  } else if (shape == "plane") {
    m_document.set(key + "point", std::array<double, 3>{0.0, 0.0, -0.2});
    m_document.set(key + "normal", std::array<double, 3>{0.0, 0.0, 1.0});
  } else if (shape == "mesh") {
    m_document.set(key + "file", mesh_file);
  }
  m_document.set(key + "material", materials.front());
  recheck();
  return m_check.ok();
}

void MainWindow::modify(const std::function<void(ScenarioDocument&)>& change) {
  change(m_document);
  recheck();
}

void MainWindow::register_form(KeyForm* form, bool connect_edits) {
  m_forms.push_back(form);
  if (connect_edits)
    connect(form, &KeyForm::edited, this,
            [this](const std::string& key, const TomlValue& value) { apply_edit(key, value); });
}

void MainWindow::unregister_form(KeyForm* form) {
  m_forms.erase(std::remove(m_forms.begin(), m_forms.end(), form), m_forms.end());
  form->disconnect(this);
}

bool MainWindow::remove_object(std::size_t index) {
  m_document.erase_table("render.objects", index);
  recheck();
  return m_check.ok();
}

void MainWindow::recheck() {
  m_check = m_document.check();
  const QString message = QString::fromStdString(m_check.message);
  bool shown = false;
  for (KeyForm* form : m_forms) shown |= form->show_problem(m_check.key, message);
  // A problem no field edits (or a key in another tab) is shown above the tabs as well.
  m_problem->setText(message);
  m_problem->setVisible(!m_check.ok() && !shown);
  if (m_save) m_save->setEnabled(m_check.ok());
  if (m_save_as) m_save_as->setEnabled(m_check.ok());
  if (m_check.ok()) {
    for (KeyForm* form : m_forms) form->refresh(*m_check.scenario);
    grey_out_unused(*m_check.scenario);
    const RunScenario& sc = *m_check.scenario;
    if (m_run &&
        (m_run->simulation_text != sc.simulation_text || m_run->mesh_text != sc.mesh_text)) {
      // The run no longer matches the scenario: back to the initial shell.
      m_run.reset();
      m_step = -1;
      show_flow_speed();
      m_slider->setEnabled(false);
      m_plot->set_rows({});
      m_sim_status->setText("The scenario changed: simulate again to scrub through time.");
      if (auto shell = m_renderer->initial_shell())
        m_view->show_step(*shell, shell_offset_of(*shell), false);
    }
    request_preview();
  } else {
    m_status->setText("not rendered: " + message);
  }
  if (m_scene) m_scene->refresh();
  update_title();
}

void MainWindow::switch_solver_family(const std::string& geometry) {
  // [shell] is the 1D geometries' table, [shape] the grid solvers' (the parser rejects the other
  // one, and the keys only one solver reads): switching between them carries the body over, a
  // hollow sphere as spheres (a grid body that is no sphere becomes the 1D default's radii).
  const bool to_grid = geometry == "axisymmetric" || geometry == "3d";
  if (!m_check.ok()) return;
  const sim::Scenario& s = m_check.scenario->simulation;
  const bool grid = s.grid != sim::GridGeometry::none;
  if (to_grid == grid) return;
  if (to_grid) {
    const double outer = s.outer_radius_m, inner = s.inner_radius_m;
    m_document.remove("shell");
    for (const char* key : {"simulation.cells_per_phase", "simulation.time_tolerance"})
      m_document.remove(key);
    m_document.set("shape.outer.kind", std::string("sphere"));
    m_document.set("shape.outer.radius_m", outer);
    if (inner > 0) {
      m_document.set("shape.cavity.kind", std::string("sphere"));
      m_document.set("shape.cavity.radius_m", inner);
    }
    return;
  }
  const bool spheres = s.shape.outer.kind == sim::ShapeKind::sphere &&
                       (!s.shape.cavity || s.shape.cavity->kind == sim::ShapeKind::sphere);
  const double outer = spheres ? s.shape.outer.radius_m : 0.03;
  const double inner = spheres ? (s.shape.cavity ? s.shape.cavity->radius_m : 0.0) : 0.02;
  for (const char* key :
       {"shape", "simulation.cell_size_m", "simulation.max_step_s", "simulation.flow"})
    m_document.remove(key);
  m_document.set("shell.outer_radius_m", outer);
  m_document.set("shell.inner_radius_m", inner);
}

void MainWindow::fit_keys_to_kind(const std::string& kind_key) {
  // The parsers' rule: a table holds exactly the keys its kind uses (an outer boundary's
  // temperature, h or flux; a sphere light's radius; a material's texture). After a kind
  // changed, a key of that table the parser rejects as not used is removed and one it misses
  // is added with a typical value, so that switching a kind is one edit, not an error whose key
  // the window has no field to remove. A rejected value is left alone (its message shows).
  // Typical values by "kind/key" or, failing that, by the key's last part: a held outer
  // temperature below melting (the rules reject a held one above), convective air at 20 C.
  static const std::map<std::string, TomlValue> typical = {
      {"temperature/temperature_c", TomlValue{-10.0}},
      {"temperature_c", TomlValue{20.0}},
      {"heat_transfer_coefficient_w_m2k", TomlValue{10.0}},
      {"flux_w_m2", TomlValue{1000.0}},
      {"relative_humidity", TomlValue{0.5}},
      {"radius", TomlValue{0.1}},
      // [shape] bodies (issue 25): a 3 cm cube, sphere or cylinder, small enough to be a
      // cavity in the shipped 4 cm bodies
      {"size_m", TomlValue{std::array<double, 3>{0.03, 0.03, 0.03}}},
      {"radius_m", TomlValue{0.015}},
      {"height_m", TomlValue{0.03}},
      {"emission", TomlValue{std::array<double, 3>{1.0, 1.0, 1.0}}}};
  const std::string kind = m_document.string_or(kind_key, "");
  const std::string table = kind_key.substr(0, kind_key.size() - std::string(".kind").size());
  for (int k = 0; k < 8; ++k) {
    const ScenarioCheck c = m_document.check();
    if (c.ok() || c.key.rfind(table + ".", 0) != 0) return;
    const bool unused = c.message.find("unknown key") != std::string::npos ||
                        c.message.find("not used") != std::string::npos ||
                        c.message.find("only used") != std::string::npos;
    const std::string part = c.key.substr(table.size() + 1);
    auto t = typical.find(kind + "/" + part);
    if (t == typical.end()) t = typical.find(part);
    if (unused && m_document.has(c.key))
      m_document.remove(c.key);
    else if (!m_document.has(c.key) && t != typical.end())
      m_document.set(c.key, t->second);
    else
      return;
  }
}

void MainWindow::grey_out_unused(const RunScenario& sc) {
  // Keys the scenario's geometry or outer boundary does not read stay editable in the file but
  // are greyed out here (a sphere has no length; an insulated boundary no temperature).
  using B = sim::OuterBoundary;
  const sim::Scenario& s = sc.simulation;
  const std::pair<const char*, bool> used[] = {
      {"shell.length_m", s.geometry == sim::Geometry::cylinder},
      {"shell.lateral_size_m", s.geometry == sim::Geometry::planar},
      {"outer_boundary.temperature_c",
       s.outer_kind == B::temperature || s.outer_kind == B::convective || s.outer_kind == B::air},
      {"outer_boundary.heat_transfer_coefficient_w_m2k", s.outer_kind == B::convective},
      {"outer_boundary.flux_w_m2", s.outer_kind == B::flux},
      {"outer_boundary.relative_humidity", s.outer_kind == B::air},
      {"outer_boundary.speed_m_s", s.outer_kind == B::air},
      {"outer_boundary.surroundings_temperature_c", s.outer_kind == B::air},
      {"outer_boundary.emissivity", s.outer_kind == B::air},
  };
  for (const auto& [key, on] : used)
    for (KeyForm* form : m_forms)
      if (QWidget* field = form->field(key)) field->setEnabled(on);
  // A grid scenario's [shape] rows instead of the 1D radii; of a body's rows those of its kind.
  const bool grid = s.grid != sim::GridGeometry::none;
  m_shell_form->setVisible(!grid);
  m_shape_form->setVisible(grid);
  using K = sim::ShapeKind;
  for (const auto& [table, spec] :
       {std::pair{std::string("shape.outer"), std::optional<sim::ShapeSpec>(s.shape.outer)},
        std::pair{std::string("shape.cavity"), s.shape.cavity}}) {
    const std::optional<K> kind = grid && spec ? std::optional<K>(spec->kind) : std::nullopt;
    const std::pair<const char*, bool> keys[] = {
        {".center_m", kind.has_value()},    {".size_m", kind == K::box},
        {".edge_radius_m", kind == K::box}, {".radius_m", kind == K::sphere || kind == K::cylinder},
        {".height_m", kind == K::cylinder}, {".scale", kind == K::obj},
        {".translate_m", kind == K::obj},
    };
    for (const auto& [key, on] : keys)
      if (QWidget* field = m_shape_form->field(table + key)) field->setEnabled(on);
  }
}

bool MainWindow::can_save() const {
  return m_check.ok();
}

QString MainWindow::field_problem(const std::string& key) const {
  for (KeyForm* form : m_forms)
    if (form->field(key)) return form->problem(key);
  return {};
}

void MainWindow::open_file(const std::filesystem::path& path) {
  m_document = ScenarioDocument::load(path);
  m_path = path;
  recheck();
}

bool MainWindow::save_file(const std::filesystem::path& path) {
  recheck();
  if (!m_check.ok()) return false;
  try {
    m_document.save(path);
  } catch (const UserError& e) {
    m_status->setText(QString::fromStdString(e.what()));
    return false;
  }
  m_path = path;
  m_document.set_source_name(path.string());
  m_status->setText("saved " + QString::fromStdString(path.string()) +
                    (m_document.layout_kept()
                         ? QString()
                         : QString(" (an edit could not be made in place: the file was written "
                                   "anew, without its comments)")));
  update_title();
  return true;
}

bool MainWindow::start_film(const std::filesystem::path& dir) {
  if (!m_check.ok() || m_film->running()) return false;
  if (!m_film->start(*m_check.scenario, m_document.text(), dir)) return false;
  m_film_button->setEnabled(false);
  m_film_cancel->setEnabled(true);
  m_film_progress->setRange(0, static_cast<int>(pipeline::frame_times(*m_check.scenario).size()));
  m_film_progress->setValue(0);
  m_film_progress->setFormat("%v / %m frames");
  m_film_status->setText("Running thaw run into " + QString::fromStdString(dir.string()) + "...");
  m_film_poll->start();
  return true;
}

void MainWindow::cancel_film() {
  if (!m_film->running()) return;
  m_film->cancel();
  m_film_cancel->setEnabled(false);
  m_film_status->setText("Cancelling: the run stops at its next safe point...");
}

bool MainWindow::film_running() const {
  return m_film->running();
}

void MainWindow::show_frame(int index) {
  if (index < 0 || index >= static_cast<int>(m_frames.size())) return;
  const QImage frame(QString::fromStdString(m_frames[static_cast<std::size_t>(index)].string()));
  if (frame.isNull()) return;
  m_image = frame;
  show_image();
  m_status->setText(QString("film frame %1/%2").arg(index + 1).arg(m_frames.size()));
  m_frame_label->setText(QString("frame %1/%2").arg(index + 1).arg(m_frames.size()));
}

bool is_tab_title(const std::string& name) {
  for (const char* title : kTabTitles)
    if (QString::fromStdString(name).compare(title, Qt::CaseInsensitive) == 0) return true;
  return false;
}

bool MainWindow::select_tab(const std::string& name) {
  for (int k = 0; k < m_tabs->count(); ++k)
    if (m_tabs->tabText(k).compare(QString::fromStdString(name), Qt::CaseInsensitive) == 0) {
      m_tabs->setCurrentIndex(k);
      return true;
    }
  return false;
}

void MainWindow::set_preview_size(int width, int height) {
  m_preview_width = width;
  m_preview_height = height;
  request_preview();
}

void MainWindow::request_preview(bool full_quality) {
  if (!m_check.ok()) return;
  const RunScenario& sc = *m_check.scenario;
  PreviewRequest r;
  r.scenario = sc;
  const render::ImageSettings& image = sc.scene.image;
  if (full_quality) {
    r.width = image.width, r.height = image.height;
  } else {
    // The film's aspect ratio at the preview's width.
    r.width = m_preview_width;
    r.height = std::max(
        1, static_cast<int>(std::lround(double(m_preview_width) * image.height / image.width)));
    m_preview_height = r.height;
  }
  r.samples = image.samples_per_pixel;
  if (m_run && m_step >= 0) {
    r.step = m_run->steps[static_cast<std::size_t>(m_step)];
    r.camera_rows = m_run->rows;
  }
  m_full_quality = full_quality;
  m_request_size = QSize(r.width, r.height);
  m_pass = -1;
  m_request_serial = m_renderer->request(std::move(r));
}

void MainWindow::on_image(const QImage& image, int pass, int passes, double seconds,
                          quint64 serial) {
  if (serial != m_request_serial) return;  // queued before the newer request was made
  m_image = image;
  m_pass = pass;
  m_passes = passes;
  m_seconds = seconds;
  show_image();
  m_status->setText(QString("preview pass %1/%2: %3 x %4 in %5 s")
                        .arg(pass + 1)
                        .arg(passes)
                        .arg(image.width())
                        .arg(image.height())
                        .arg(seconds, 0, 'f', 2));
  emit previewShown(pass);
  if (pass + 1 == passes) emit previewFinished();
}

void MainWindow::show_image() {
  if (m_image.isNull()) return;
  const QSize room = m_preview->size() - QSize(4, 4);
  m_preview->setPixmap(
      QPixmap::fromImage(m_image.scaled(room, Qt::KeepAspectRatio, Qt::SmoothTransformation)));
}

void MainWindow::resizeEvent(QResizeEvent* event) {
  QMainWindow::resizeEvent(event);
  show_image();
}

std::array<double, 3> MainWindow::shell_offset_of(const ShellStep& step) const {
  if (!m_check.ok()) return {0.0, 0.0, 0.0};
  std::optional<double> min_y;
  if (step.outer && !step.outer->positions.empty()) {
    min_y = step.outer->positions.front().y;
    for (const auto& p : step.outer->positions) min_y = std::min<double>(*min_y, p.y);
  }
  return pipeline::shell_offset(*m_check.scenario, min_y);
}

void MainWindow::camera_from_view() {
  if (!m_check.ok()) return;
  // The view is in scene coordinates (the shell drawn where the frames place it). Written to a
  // micrometre (and the up direction and angle to 1e-6), so the file and the Scene tab read
  // 0.126686 rather than 0.12668567722...: far below what a frame resolves (the smallest shell
  // is millimetres across), and the parser normalises the up vector.
  const ShellView::ViewCamera v = m_view->camera();
  auto rounded = [](double x) { return std::round(x * 1e6) / 1e6; };
  auto rounded3 = [&](const std::array<double, 3>& a, double scale) {
    return std::array<double, 3>{rounded(a[0] / scale), rounded(a[1] / scale),
                                 rounded(a[2] / scale)};
  };
  const double n = std::hypot(v.view_up[0], v.view_up[1], v.view_up[2]);
  modify([&](ScenarioDocument& d) {
    d.set("render.camera.position", rounded3(v.position, 1.0));
    d.set("render.camera.look_at", rounded3(v.focal_point, 1.0));
    d.set("render.camera.up", rounded3(v.view_up, n));
    d.set("render.camera.vertical_fov_deg", rounded(v.vertical_fov_deg));
  });
}

void MainWindow::on_shell_ready() {
  // A run's step shown meanwhile (the slider, or --simulate finishing before the initial shell
  // was meshed) stays: the view shows the initial shell only without one.
  if (m_run && m_step >= 0) return;
  if (auto shell = m_renderer->initial_shell()) {
    m_view->show_step(*shell, shell_offset_of(*shell), true);
    if (!shell->note.empty()) m_status->setText(QString::fromStdString(shell->note));
  }
}

void MainWindow::update_title() {
  const QString name =
      m_path.empty() ? "built-in default" : QString::fromStdString(m_path.filename().string());
  setWindowTitle("thaw gui - " + name + (m_check.ok() ? "" : " (has a problem)"));
}

}  // namespace thaw::gui
