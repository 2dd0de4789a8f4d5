// The workbench window (QTest, under $DISPLAY or a private Xvfb): editing through the fields,
// saving and reloading; a bad value's message and blocked saving; an added object changing the
// preview; a stale preview cancelled by an edit; cancelling and resuming "Render film"; the
// screenshot of the default with its panels and a non-empty render.
#include <vtkActor.h>
#include <QApplication>
#include <QComboBox>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QPointer>
#include <QProgressBar>
#include <QPushButton>
#include <QScreen>
#include <QSignalSpy>
#include <QSlider>
#include <QTabWidget>
#include <QtTest>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <string>

#include "base/interrupt.h"
#include "sim/grid/grid_rules.h"
#include "src/gui/main_window.h"
#include "src/gui/scene_props.h"
#include "src/gui/screenshot.h"
#include "src/gui/shell_view.h"
#include "src/inspect/virtual_display.h"

namespace fs = std::filesystem;
using thaw::gui::MainWindow;
using thaw::gui::ScenarioDocument;

namespace {

fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() /
                       ("thaw_gui_window_" + std::to_string(QCoreApplication::applicationPid()));
  fs::create_directories(dir);
  return dir;
}

/// Types `text` into the line edit of `key` as a user would, then leaves the field.
void type_into(MainWindow& w, const std::string& key, const QString& text) {
  // Numbers are a line edit named after the key; vectors a line edit "<key>.text" beside a picker.
  auto* edit = w.findChild<QLineEdit*>(QString::fromStdString(key));
  if (!edit) edit = w.findChild<QLineEdit*>(QString::fromStdString(key + ".text"));
  QVERIFY2(edit, key.c_str());
  edit->setFocus();
  edit->selectAll();
  QTest::keyClicks(edit, text);
  QTest::keyClick(edit, Qt::Key_Return);
}

/// Mean absolute difference of two images of the same size, per channel [0, 255].
double mean_difference(const QImage& a, const QImage& b) {
  if (a.size() != b.size()) return 255;
  double sum = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const QRgb p = a.pixel(x, y), q = b.pixel(x, y);
      sum += std::abs(qRed(p) - qRed(q)) + std::abs(qGreen(p) - qGreen(q)) +
             std::abs(qBlue(p) - qBlue(q));
    }
  return sum / (3.0 * a.width() * a.height());
}

/// Mean grey level of `image` [0, 255].
double mean_grey(const QImage& image) {
  double s = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) s += qGray(image.pixel(x, y));
  return s / std::max(1, image.width() * image.height());
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Standard deviation of the grey level over `r` of `image`.
double grey_spread(const QImage& image, const QRect& r) {
  double s = 0, s2 = 0;
  long n = 0;
  for (int y = r.top(); y <= r.bottom(); ++y)
    for (int x = r.left(); x <= r.right(); ++x) {
      const double g = qGray(image.pixel(x, y));
      s += g, s2 += g * g, ++n;
    }
  const double mean = s / n;
  return std::sqrt(std::max(0.0, s2 / n - mean * mean));
}

/// Waits for the first image of the current scenario at the preview's full size.
bool wait_for_full_size(MainWindow& w, int timeout_ms = 60000) {
  QElapsedTimer t;
  t.start();
  while (t.elapsed() < timeout_ms) {
    QCoreApplication::processEvents(QEventLoop::AllEvents, 20);
    if (w.preview_full_size()) return true;
    QTest::qWait(10);
  }
  return false;
}

}  // namespace

class TestMainWindow : public QObject {
  Q_OBJECT
 private slots:
  void editSaveReloadCompare() {
    MainWindow w{ScenarioDocument()};
    w.show();
    type_into(w, "shell.outer_radius_m", "0.032");
    type_into(w, "render.image.samples_per_pixel", "8");
    QVERIFY2(w.check().ok(), w.check().message.c_str());
    const fs::path file = temp_dir() / "edited.toml";
    QVERIFY(w.save_file(file));
    MainWindow back{ScenarioDocument::load(file)};
    QVERIFY2(back.check().ok(), back.check().message.c_str());
    const auto& a = *w.check().scenario;
    const auto& b = *back.check().scenario;
    QCOMPARE(b.simulation.outer_radius_m, 0.032);
    QCOMPARE(b.scene.image.samples_per_pixel, 8);
    QCOMPARE(a.simulation_text, b.simulation_text);
    QCOMPARE(a.render_text, b.render_text);
    QCOMPARE(a.film_text, b.film_text);
    QCOMPARE(a.mesh_text, b.mesh_text);
    // The reloaded window's field shows the saved value.
    auto* edit = back.findChild<QLineEdit*>("shell.outer_radius_m");
    QVERIFY(edit);
    QCOMPARE(edit->text(), QString("0.032"));
  }

  // Fields of keys the scenario does not read are greyed out: a sphere has no length, a
  // convective boundary no flux; switching a kind brings the keys the new kind reads.
  void fieldsTheScenarioDoesNotReadAreGreyedOut() {
    MainWindow w{ScenarioDocument()};  // a sphere, a convective outer boundary
    auto enabled = [&](const char* key) {
      auto* f = w.findChild<QLineEdit*>(key);
      return f && f->isEnabled();
    };
    QVERIFY(!enabled("shell.length_m"));
    QVERIFY(!enabled("shell.lateral_size_m"));
    QVERIFY(enabled("outer_boundary.heat_transfer_coefficient_w_m2k"));
    QVERIFY(!enabled("outer_boundary.flux_w_m2"));
    QVERIFY(w.apply_edit("simulation.geometry", std::string("cylinder")));
    QVERIFY(enabled("shell.length_m"));
    // Switching a kind is one edit: the keys the new kind does not read go, those it needs come
    // with a typical value (the files' rule: a table holds exactly the keys its kind uses).
    QVERIFY2(w.apply_edit("outer_boundary.kind", std::string("flux")), w.check().message.c_str());
    QVERIFY(enabled("outer_boundary.flux_w_m2"));
    QVERIFY(!enabled("outer_boundary.heat_transfer_coefficient_w_m2k"));
    QVERIFY(!enabled("outer_boundary.temperature_c"));
    QVERIFY(!w.document().has("outer_boundary.temperature_c"));
    QCOMPARE(w.check().scenario->simulation.flux_w_m2, 1000.0);
    QVERIFY2(w.apply_edit("outer_boundary.kind", std::string("convective")),
             w.check().message.c_str());
    QVERIFY(!w.document().has("outer_boundary.flux_w_m2"));
    QCOMPARE(w.check().scenario->simulation.heat_transfer_coefficient_w_m2k, 10.0);
    QCOMPARE(w.check().scenario->simulation.outer_temperature_c, 20.0);
    // A held temperature must not be above melting (the rules): a new one is -10 C; an air
    // temperature kept from the convective kind is the user's value, shown with its message.
    QVERIFY(!w.apply_edit("outer_boundary.kind", std::string("temperature")));
    QVERIFY(!w.field_problem("outer_boundary.temperature_c").isEmpty());
    QVERIFY2(w.apply_edit("outer_boundary.kind", std::string("insulated")),
             w.check().message.c_str());
    QVERIFY2(w.apply_edit("outer_boundary.kind", std::string("temperature")),
             w.check().message.c_str());
    QCOMPARE(w.check().scenario->simulation.outer_temperature_c, -10.0);
    // Room air (issue 25): its humidity comes with a typical 50 %, its fields light up, the
    // air temperature is kept; back to convective they go again.
    QVERIFY2(w.apply_edit("outer_boundary.kind", std::string("air")), w.check().message.c_str());
    QCOMPARE(w.check().scenario->simulation.relative_humidity, 0.5);
    QVERIFY(enabled("outer_boundary.relative_humidity"));
    QVERIFY(enabled("outer_boundary.speed_m_s"));
    QVERIFY(enabled("outer_boundary.temperature_c"));
    QVERIFY(!enabled("outer_boundary.heat_transfer_coefficient_w_m2k"));
    QVERIFY2(w.apply_edit("outer_boundary.kind", std::string("convective")),
             w.check().message.c_str());
    QVERIFY(!w.document().has("outer_boundary.relative_humidity"));
    QVERIFY(!enabled("outer_boundary.relative_humidity"));
    // The same for any kind: a sphere light turned point loses its radius, and back gets one.
    QVERIFY2(w.apply_edit("render.lights[0].kind", std::string("point")),
             w.check().message.c_str());
    QVERIFY(!w.document().has("render.lights[0].radius"));
    QVERIFY2(w.apply_edit("render.lights[0].kind", std::string("sphere")),
             w.check().message.c_str());
    QCOMPARE(w.check().scenario->scene.lights[0].radius, 0.1);
  }

  void badValueShowsItsMessageAndBlocksSaving() {
    MainWindow w{ScenarioDocument()};
    w.show();
    type_into(w, "shell.inner_radius_m", "0.04");  // outside the 0.03 m outer radius
    QVERIFY(!w.check().ok());
    QVERIFY(!w.can_save());
    const QString shown = w.field_problem(w.check().key);
    QVERIFY2(!shown.isEmpty(), w.check().key.c_str());
    QCOMPARE(shown.toStdString(), w.check().message);
    const fs::path file = temp_dir() / "refused.toml";
    fs::remove(file);
    QVERIFY(!w.save_file(file));
    QVERIFY(!fs::exists(file));
    // Fixing the value clears the message and allows saving again.
    type_into(w, "shell.inner_radius_m", "0.02");
    QVERIFY(w.check().ok());
    QVERIFY(w.field_problem("shell.inner_radius_m").isEmpty());
    QVERIFY(w.can_save());
  }

  void addedObjectChangesThePreview() {
    MainWindow w{ScenarioDocument()};
    w.show();
    QVERIFY(wait_for_full_size(w));
    const QImage before = w.preview_image();
    // The Scene tab's "Add object" (a sphere by default), then its radius typed into the form
    // of the new, selected object.
    const std::size_t before_count = w.document().array_size("render.objects");
    auto* add = w.findChild<QPushButton*>("add_object");
    QVERIFY(add);
    add->click();
    QCOMPARE(w.document().array_size("render.objects"), before_count + 1);
    const std::string key = "render.objects[" + std::to_string(before_count) + "]";
    type_into(w, key + ".center", "0, 0.02, 0");
    type_into(w, key + ".radius", "0.05");
    QVERIFY2(w.check().ok(), w.check().message.c_str());
    QCOMPARE(w.check().scenario->scene.objects.back().radius, 0.05);
    QVERIFY(wait_for_full_size(w));
    const QImage after = w.preview_image();
    QCOMPARE(after.size(), before.size());
    // A sphere filling much of the frame changes far more than noise would (the passes are
    // deterministic: the same scene renders the same image).
    QVERIFY2(mean_difference(before, after) > 5.0,
             qPrintable(QString::number(mean_difference(before, after))));
  }

  void sceneTabEditsLightsMaterialsAndMedia() {
    MainWindow w{ScenarioDocument()};
    w.show();
    // A checker texture's colour, through its form.
    type_into(w, "render.materials.floor.checker.colors[1]", "0.1, 0.3, 0.6");
    QVERIFY2(w.check().ok(), w.check().message.c_str());
    const auto& floor = w.check().scenario->scene.materials.front();
    QCOMPARE(floor.texture.checker_colors[1], (thaw::render::RgbD{0.1, 0.3, 0.6}));
    // A light's intensity; a negative one is the parser's problem, shown under the field.
    type_into(w, "render.lights[0].intensity", "-1");
    QVERIFY(!w.check().ok());
    QVERIFY(!w.field_problem("render.lights[0].intensity").isEmpty());
    type_into(w, "render.lights[0].intensity", "0.5");
    QVERIFY(w.check().ok());
    QCOMPARE(w.check().scenario->scene.lights.front().intensity, 0.5);
    // The ice medium's index as Sellmeier coefficients.
    w.modify([](ScenarioDocument& d) {
      d.remove("render.media.ice.ior");
      d.remove("render.media.ice.preset");
      d.set("render.media.ice.sellmeier.B", std::array<double, 3>{0.7, 0.0, 0.0});
      d.set("render.media.ice.sellmeier.C", std::array<double, 3>{0.01, 0.0, 0.0});
    });
    QVERIFY2(w.check().ok(), w.check().message.c_str());
  }

  // The report's "transparent" material: an object's surface switched to a dielectric between
  // media in its Scene form (and back to an opaque material).
  void anObjectTurnsDielectricAndBack() {
    MainWindow w{ScenarioDocument()};
    w.show();
    QVERIFY(w.select_tab("scene"));
    QVERIFY(w.add_object("sphere"));
    const std::size_t k = w.document().array_size("render.objects") - 1;
    const std::string key = "render.objects[" + std::to_string(k) + "]";
    auto* list = w.findChild<QListWidget*>("objects_list");
    QVERIFY(list);
    list->setCurrentRow(static_cast<int>(k));  // its form, as a click on it shows
    auto* surface = w.findChild<QComboBox*>(QString::fromStdString(key + ".surface"));
    QVERIFY(surface);
    QCOMPARE(surface->currentIndex(), 0);
    surface->setCurrentIndex(1);
    QVERIFY2(w.check().ok(), w.check().message.c_str());
    const auto& dielectric = w.check().scenario->scene.objects.back();
    QVERIFY(dielectric.is_dielectric());
    QCOMPARE(dielectric.inside, w.document().table_keys("render.media").front());
    QCOMPARE(dielectric.outside, w.check().scenario->shell.outside_medium);
    // The form of the object is made anew (the old one deleted): it now edits its media.
    const QPointer<QComboBox> old_surface(surface);
    QTRY_VERIFY_WITH_TIMEOUT(old_surface.isNull(), 5000);
    QVERIFY(w.findChild<QComboBox*>(QString::fromStdString(key + ".inside")));
    auto* back = w.findChild<QComboBox*>(QString::fromStdString(key + ".surface"));
    QVERIFY(back);
    QCOMPARE(back->currentIndex(), 1);
    back->setCurrentIndex(0);
    QVERIFY2(w.check().ok(), w.check().message.c_str());
    QVERIFY(!w.check().scenario->scene.objects.back().is_dielectric());
    QVERIFY(!w.document().has(key + ".inside"));
  }

  void orbitingTheViewWritesTheCameraBack() {
    MainWindow w{ScenarioDocument()};
    w.show();
    QTRY_VERIFY_WITH_TIMEOUT(w.shell_view().triangles() > 0 && w.shell_view().scene_objects() > 0,
                             120000);
    QVERIFY(!w.check().scenario->camera_set);
    // As an orbit ends: the view (in scene coordinates) looks from +x, slightly above, at the
    // shell's core, which the default places 3 cm above the floor at y = 0.
    // An orbit's start and end, as a mouse drag makes them: drawn quick (no edges) meanwhile.
    QVERIFY(!w.shell_view().quick());
    w.shell_view().begin_interaction();
    QVERIFY(w.shell_view().quick());
    w.shell_view().set_camera({{0.2, 0.08, 0.0}, {0.0, 0.03, 0.0}, {0.0, 1.0, 0.0}, 30.0});
    w.shell_view().end_interaction();
    // At rest again with the scene of the new camera (or after ShellView::kSettleMs).
    QTRY_VERIFY_WITH_TIMEOUT(!w.shell_view().quick(), 10000);
    QVERIFY2(w.check().ok(), w.check().message.c_str());
    const auto& sc = *w.check().scenario;
    QVERIFY(sc.camera_set);
    const auto& cam = sc.scene.camera;
    QCOMPARE(cam.position, (thaw::render::Vec3d{0.2, 0.08, 0.0}));
    QCOMPARE(cam.look_at, (thaw::render::Vec3d{0.0, 0.03, 0.0}));
    QCOMPARE(cam.vertical_fov_deg, 30.0);
    // The preview renders from there: its next images come with that camera, and the view keeps
    // it (the written-back camera does not move the view again).
    QVERIFY(wait_for_full_size(w));
    const auto v = w.shell_view().camera();
    QCOMPARE(v.position, (std::array<double, 3>{0.2, 0.08, 0.0}));
    // A camera the mouse left anywhere is written to a micrometre (the Scene tab and the file
    // read 0.123457, not 0.123456789).
    w.shell_view().begin_interaction();
    w.shell_view().set_camera(
        {{0.123456789, 0.0812345678, 0.01}, {0.0, 0.03, 0.0}, {0.0, 1.0, 0.0}, 30.123456789});
    w.shell_view().end_interaction();
    QVERIFY2(w.check().ok(), w.check().message.c_str());
    const auto& moved = w.check().scenario->scene.camera;
    QCOMPARE(moved.position, (thaw::render::Vec3d{0.123457, 0.081235, 0.01}));
    QCOMPARE(moved.vertical_fov_deg, 30.123457);
  }

  // The 3D view shows the frame's scene, not only the shell: the default's floor and light, an
  // object added in the Scene tab, and the camera set in the Scene tab.
  void theViewShowsTheSceneAndItsCamera() {
    MainWindow w{ScenarioDocument()};
    w.show();
    QTRY_VERIFY_WITH_TIMEOUT(w.shell_view().scene_objects() == 1, 120000);  // the floor plane
    QCOMPARE(w.shell_view().scene_lights(), std::size_t{1});
    // Until the scenario sets a camera the view looks through the built-in framing camera.
    const auto framing = w.shell_view().camera();
    QVERIFY(framing.vertical_fov_deg > 1.0);
    QVERIFY(w.add_object("box"));
    QTRY_VERIFY_WITH_TIMEOUT(w.shell_view().scene_objects() == 2, 60000);
    QVERIFY(w.add_object("sphere"));
    QTRY_VERIFY_WITH_TIMEOUT(w.shell_view().scene_objects() == 3, 60000);
    QVERIFY(w.remove_object(1));
    QTRY_VERIFY_WITH_TIMEOUT(w.shell_view().scene_objects() == 2, 60000);
    // A camera typed into the Scene tab moves the view's camera.
    type_into(w, "render.camera.position", "0.1, 0.3, 0.4");
    QVERIFY2(w.check().ok(), w.check().message.c_str());
    QTRY_VERIFY_WITH_TIMEOUT(
        w.shell_view().camera().position == (std::array<double, 3>{0.1, 0.3, 0.4}), 60000);
  }

  // The view is drawn on its render thread (view_render_thread.h) and painted from the images it
  // sends: the latest request wins (a burst of camera moves made while a draw is in progress is
  // drawn once, with the last camera), and the frame shown is the last request's.
  void theViewDrawsTheLatestRequestOffTheGuiThread() {
    MainWindow w{ScenarioDocument()};
    w.show();
    thaw::gui::ShellView& v = w.shell_view();
    QTRY_VERIFY_WITH_TIMEOUT(v.triangles() > 0 && v.scene_objects() > 0 && !v.drawing(), 120000);
    QVERIFY(!v.image().isNull());
    QCOMPARE(v.image().size(), v.size() * v.devicePixelRatioF());
    const long shown = v.frames_shown();
    QVERIFY(shown > 0);
    // 20 orbit steps without serving the event loop: each returns at once (no draw on this
    // thread), and at most a few frames come of them, the last with the last camera.
    const auto c0 = v.camera();
    QElapsedTimer t;
    t.start();
    for (int k = 1; k <= 20; ++k) v.set_camera(thaw::gui::orbit(c0, 2.0 * k, 0.0));
    QVERIFY2(t.elapsed() < 100, qPrintable(QString::number(t.elapsed())));
    QVERIFY(v.drawing());
    QTRY_VERIFY_WITH_TIMEOUT(!v.drawing(), 20000);
    QVERIFY2(v.frames_shown() - shown < 20, qPrintable(QString::number(v.frames_shown() - shown)));
    const QImage last = v.image();
    // The same camera drawn again: the same pixels (the frame shown was the last request's).
    v.set_camera(thaw::gui::orbit(c0, 40.0, 0.0));
    QTRY_VERIFY_WITH_TIMEOUT(!v.drawing(), 20000);
    QCOMPARE(mean_difference(v.image(), last), 0.0);
    // and another camera, other pixels
    v.set_camera(c0);
    QTRY_VERIFY_WITH_TIMEOUT(!v.drawing(), 20000);
    QVERIFY(mean_difference(v.image(), last) > 1.0);
  }

  // The ice's triangle edges are drawn only where they read as a mesh (ShellView::kEdgeMinPx
  // apart on the screen, and at rest): at the default framing (2.5 mm edges) they were 1-pixel
  // lines a few pixels apart, salt-and-pepper over the ice and the water behind it.
  void theIceEdgesAreDrawnOnlyWhereTheyReadAsAMesh() {
    MainWindow w{ScenarioDocument()};
    w.show();
    thaw::gui::ShellView& v = w.shell_view();
    QTRY_VERIFY_WITH_TIMEOUT(v.triangles() > 0 && v.scene_objects() > 0 && !v.drawing(), 120000);
    QVERIFY(!v.quick());
    QVERIFY(!v.edges_shown());
    // Four times closer: the edges four times longer on the screen.
    v.set_camera(thaw::gui::dolly(v.camera(), 4.0));
    QVERIFY(v.edges_shown());
    v.begin_interaction();
    QVERIFY(!v.edges_shown());  // quick
    v.end_interaction();
  }

  // A mouse drag on the view orbits its camera about the focal point (left button), drawn quick
  // while it lasts, and its release writes the camera back as the scenario's [render.camera].
  void aMouseDragOrbitsTheViewAndWritesTheCameraBack() {
    MainWindow w{ScenarioDocument()};
    w.show();
    thaw::gui::ShellView& v = w.shell_view();
    QTRY_VERIFY_WITH_TIMEOUT(v.triangles() > 0 && v.scene_objects() > 0 && !v.drawing(), 120000);
    QTRY_VERIFY_WITH_TIMEOUT(w.check().ok() && w.preview_full_size(), 120000);
    const auto c0 = v.camera();
    const QPoint from(v.width() / 2, v.height() / 2), to = from + QPoint(v.width() / 10, 0);
    QMouseEvent press(QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::LeftButton,
                      Qt::NoModifier);
    QApplication::sendEvent(&v, &press);
    QVERIFY(v.quick());
    QMouseEvent move(QEvent::MouseMove, to, Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(&v, &move);
    QMouseEvent release(QEvent::MouseButtonRelease, to, Qt::LeftButton, Qt::NoButton,
                        Qt::NoModifier);
    QApplication::sendEvent(&v, &release);
    // VTK's trackball: a tenth of the width is -20 degrees of azimuth about the view-up.
    const auto c1 = v.camera();
    const auto expected = thaw::gui::orbit(c0, -200.0 * (to.x() - from.x()) / v.width(), 0.0);
    for (int k = 0; k < 3; ++k) QVERIFY(std::abs(c1.position[k] - expected.position[k]) < 1e-9);
    QVERIFY2(w.check().ok(), w.check().message.c_str());
    const auto& cam = w.check().scenario->scene.camera;
    for (int k = 0; k < 3; ++k) QVERIFY(std::abs(cam.position[k] - c1.position[k]) <= 5e-7);
    QTRY_VERIFY_WITH_TIMEOUT(!v.quick() && !v.drawing(), 10000);
  }

  void startAndCancelASimulation() {
    ScenarioDocument doc;
    doc.set("film.frames", 400LL);  // long enough that the run is still going when cancelled
    MainWindow w{doc};
    w.show();
    QSignalSpy cancelled(&w, &MainWindow::simulationCancelled);
    QSignalSpy finished(&w, &MainWindow::simulationFinished);
    auto* bar = w.findChild<QProgressBar*>("simulation_progress");
    QVERIFY(bar);
    QVERIFY(w.start_simulation());
    QVERIFY(w.simulation_running());
    QVERIFY(!w.start_simulation());  // one run at a time
    // Cancel once the solver has reported progress.
    QTRY_VERIFY_WITH_TIMEOUT(bar->value() > 0, 60000);
    w.cancel_simulation();
    QTRY_VERIFY_WITH_TIMEOUT(!w.simulation_running(), 120000);
    QTRY_COMPARE_WITH_TIMEOUT(cancelled.count(), 1, 5000);
    QCOMPARE(finished.count(), 0);
    QVERIFY(w.simulation_run() == nullptr);
  }

  void simulateAndScrubTheSlider() {
    ScenarioDocument doc;
    doc.set("film.frames", 6LL);
    MainWindow w{doc};
    w.show();
    QSignalSpy finished(&w, &MainWindow::simulationFinished);
    QVERIFY(w.start_simulation());
    QTRY_VERIFY_WITH_TIMEOUT(finished.count() == 1, 300000);
    const auto run = w.simulation_run();
    QVERIFY(run);
    // 6 frame times over the hour; those after the break-through (~38 min) are not reached.
    QCOMPARE(run->steps.size(), run->rows.size());
    QVERIFY(run->steps.size() >= 3 && run->steps.size() <= 6);
    // The radii shrink over the run and the views follow the slider.
    QVERIFY(run->rows.back().outer_radius_m < run->rows.front().outer_radius_m);
    auto* slider = w.findChild<QSlider*>("time_slider");
    QVERIFY(slider && slider->isEnabled());
    const int n = static_cast<int>(run->steps.size());
    QCOMPARE(slider->maximum(), n - 1);
    slider->setValue(0);
    const long first = w.shell_view().triangles();
    QVERIFY(first > 100);
    QVERIFY(wait_for_full_size(w));
    const QImage at_start = w.preview_image();
    // The last step with ice left: its preview differs from the first step's.
    int last = n - 1;
    while (last > 0 && !run->steps[static_cast<std::size_t>(last)]->outer) --last;
    QVERIFY(last > 0);
    slider->setValue(last);
    // The step's time beside the slider.
    QCOMPARE(
        w.findChild<QLabel*>("time_label")->text(),
        QString("%1 min").arg(run->rows[static_cast<std::size_t>(last)].time_s / 60.0, 0, 'f', 1));
    // While the slider moves the ice is drawn without its triangle edges; once it rests, with.
    QVERIFY(w.shell_view().quick());
    QTRY_VERIFY_WITH_TIMEOUT(!w.shell_view().quick(), 10000);
    QVERIFY(wait_for_full_size(w));
    QVERIFY(mean_difference(at_start, w.preview_image()) > 1.0);
    // An edit of the simulation makes the run stale.
    QVERIFY(w.apply_edit("water.initial_temperature_c", 12.0));
    QVERIFY(w.simulation_run() == nullptr);
    QVERIFY(!slider->isEnabled());
  }

  void renderFilmThenStepThroughItsFrames() {
    ScenarioDocument doc;
    doc.set("film.frames", 3LL);
    doc.set("render.image.width", 64LL);
    doc.set("render.image.height", 48LL);
    MainWindow w{doc};
    w.show();
    QSignalSpy finished(&w, &MainWindow::filmFinished);
    const fs::path out = temp_dir() / "film";
    fs::remove_all(out);
    QVERIFY(w.start_film(out));
    QVERIFY(w.film_running());
    QTRY_VERIFY_WITH_TIMEOUT(finished.count() == 1, 300000);
    QVERIFY(fs::exists(out / "melt.mp4"));
    QCOMPARE(static_cast<int>(w.film_frames().size()), 3);
    auto* slider = w.findChild<QSlider*>("frame_slider");
    QVERIFY(slider && slider->isEnabled());
    slider->setValue(2);
    QCOMPARE(w.preview_image().size(), QSize(64, 48));  // the frame, not the 320x240 preview
    QCOMPARE(w.findChild<QLabel*>("frame_label")->text(), QString("frame 3/3"));
  }

  // Cancel from the window uses the pipeline's interrupt: the run stops at a safe point with no
  // temporary or partial file, no film; Render film into the same folder then resumes: the
  // frames already there are kept as they were (not rendered again) and the rest are made.
  void cancelFilmLeavesNothingHalfWrittenAndResumes() {
    ScenarioDocument doc;
    doc.set("film.frames", 8LL);
    doc.set("render.image.width", 160LL);
    doc.set("render.image.height", 120LL);
    MainWindow w{doc};
    w.show();
    QSignalSpy cancelled(&w, &MainWindow::filmCancelled);
    QSignalSpy finished(&w, &MainWindow::filmFinished);
    const fs::path out = temp_dir() / "cancelled_film";
    fs::remove_all(out);
    QVERIFY(w.start_film(out));
    // Cancel once the first frame is written (the film's frames come after the simulation).
    QTRY_VERIFY_WITH_TIMEOUT(fs::exists(out / "frames/frame_000000.png") || !w.film_running(),
                             300000);
    QVERIFY2(w.film_running(), "the film finished before it could be cancelled");
    auto* cancel = w.findChild<QPushButton*>("film_cancel_button");
    QVERIFY(cancel && cancel->isEnabled());
    cancel->click();
    QTRY_VERIFY_WITH_TIMEOUT(cancelled.count() == 1, 120000);
    QCOMPARE(finished.count(), 0);
    QVERIFY(!w.film_running());
    QVERIFY(!thaw::interrupt_requested());  // lowered again for the rest of the window
    std::map<fs::path, std::string> kept;
    for (const auto& e : fs::recursive_directory_iterator(out)) {
      QVERIFY2(e.path().filename().string().find(".tmp") == std::string::npos, e.path().c_str());
      if (e.path().parent_path().filename() == "frames") kept[e.path()] = read_bytes(e.path());
    }
    QVERIFY(!kept.empty());

    QVERIFY(!fs::exists(out / "melt.mp4"));
    for (const auto& [path, bytes] : kept) {  // whole PNGs, not cut short
      QImage frame(QString::fromStdString(path.string()));
      QCOMPARE(frame.size(), QSize(160, 120));
    }
    std::map<fs::path, fs::file_time_type> written;
    for (const auto& [path, bytes] : kept) written[path] = fs::last_write_time(path);

    QVERIFY(w.start_film(out));
    QTRY_VERIFY_WITH_TIMEOUT(finished.count() == 1, 300000);
    QVERIFY(fs::exists(out / "melt.mp4"));
    // (the film's frames: film.frames = 8 less those after the break-through)
    QVERIFY2(kept.size() < w.film_frames().size(),
             "every frame had been rendered: nothing was cancelled");
    for (const auto& [path, bytes] : kept) {
      QCOMPARE(read_bytes(path), bytes);
      QVERIFY2(fs::last_write_time(path) == written[path], path.c_str());  // resumed, not redone
    }
  }

  // An edit while a pass renders abandons that pass (its remaining tiles are skipped) and the
  // window shows only the new scenario's images from then on, in pass order.
  void anEditCancelsTheStalePreview() {
    MainWindow w{ScenarioDocument()};
    w.show();
    QVERIFY(wait_for_full_size(w));
    QTRY_VERIFY_WITH_TIMEOUT(!w.renderer().busy(), 120000);
    std::vector<int> shown;
    std::vector<double> brightness;
    bool edited_b = false;
    const std::uint64_t abandoned = w.renderer().abandoned_passes();
    // Edit A brightens (exposure +2 stops); as soon as its quick pass shows, edit B darkens
    // (-2 stops): A's next pass is rendering then.
    QObject::connect(&w, &MainWindow::previewShown, &w, [&](int pass) {
      if (!edited_b) {
        QCOMPARE(pass, 0);
        brightness.push_back(mean_grey(w.preview_image()));
        edited_b = true;
        QVERIFY(w.apply_edit("render.image.exposure", -2.0));
        return;
      }
      shown.push_back(pass);
      brightness.push_back(mean_grey(w.preview_image()));
    });
    QVERIFY(w.apply_edit("render.image.exposure", 2.0));
    QTRY_VERIFY_WITH_TIMEOUT(!shown.empty() && shown.back() == w.preview_passes() - 1, 120000);
    QVERIFY(w.renderer().abandoned_passes() > abandoned);
    std::vector<int> in_order(static_cast<std::size_t>(w.preview_passes()));
    std::iota(in_order.begin(), in_order.end(), 0);
    QCOMPARE(shown, in_order);  // B's passes only, each once
    // 4 stops apart: B's images are far darker than A's (a stale A image would not be).
    for (std::size_t k = 1; k < brightness.size(); ++k)
      QVERIFY2(brightness[k] < 0.5 * brightness[0],
               qPrintable(QString("%1 vs %2").arg(brightness[k]).arg(brightness[0])));
  }

  // A grid scenario ([shape], issue 25 item 6) shows its body at t = 0 before any simulation:
  // the grid solver's first field meshed as `thaw run` meshes it, in the preview and the 3D view.
  void aGridScenarioShowsItsBodyBeforeSimulating() {
    MainWindow w{
        ScenarioDocument::load(fs::path(THAW_SOURCE_DIR) / "data/scenarios/hollow_cube.toml")};
    w.show();
    QVERIFY2(w.check().ok(), w.check().message.c_str());
    QTRY_VERIFY_WITH_TIMEOUT(w.renderer().initial_shell() != nullptr, 120000);
    const auto shell = w.renderer().initial_shell();
    QVERIFY2(shell->outer && shell->inner, shell->note.c_str());
    // The 4 cm cube and its 2.4 cm cavity, about the shape's centre: the extents within the
    // mesher's tolerance of a cell (cell_size_m default: 1/48 of the largest extent), the
    // enclosed volumes within the marching-tetrahedra error of a cell layer over the faces.
    const double cell = 0.04 / 48;
    auto extent = [](const thaw::render::TriangleMesh& m, int axis) {
      double lo = 1e9, hi = -1e9;
      for (const auto& p : m.positions) {
        const double v = axis == 0 ? p.x : axis == 1 ? p.y : p.z;
        lo = std::min(lo, v), hi = std::max(hi, v);
      }
      return hi - lo;
    };
    auto volume = [](const thaw::render::TriangleMesh& m) {
      double v = 0;  // divergence theorem over the closed, outward surface
      for (const auto& t : m.triangles) {
        const auto &a = m.positions[t[0]], &b = m.positions[t[1]], &c = m.positions[t[2]];
        v += (a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) +
              a.z * (b.x * c.y - b.y * c.x)) /
             6.0;
      }
      return v;
    };
    for (int axis = 0; axis < 3; ++axis) {
      QVERIFY2(std::abs(extent(*shell->outer, axis) - 0.04) < cell,
               qPrintable(QString::number(extent(*shell->outer, axis))));
      QVERIFY2(std::abs(extent(*shell->inner, axis) - 0.024) < cell,
               qPrintable(QString::number(extent(*shell->inner, axis))));
    }
    const double outer_area = 6 * 0.04 * 0.04, inner_area = 6 * 0.024 * 0.024;
    QVERIFY(std::abs(volume(*shell->outer) - 0.04 * 0.04 * 0.04) < outer_area * cell);
    QVERIFY(std::abs(volume(*shell->inner) - 0.024 * 0.024 * 0.024) < inner_area * cell);
    // The row of t = 0 is the grid run's own: its water is the cavity's volume.
    QVERIFY(std::abs(shell->row.liquid_volume_m3 - 0.024 * 0.024 * 0.024) < inner_area * cell);
    // The 3D view draws it: the water's blue in the view's area.
    const fs::path png = temp_dir() / "hollow_cube.png";
    fs::remove(png);
    std::string problem = "not finished";
    thaw::gui::take_screenshot_when_ready(w, png, [&](const std::string& p) { problem = p; });
    QTRY_VERIFY_WITH_TIMEOUT(problem != "not finished", 300000);
    QCOMPARE(QString::fromStdString(problem), QString());
    const QImage shot(QString::fromStdString(png.string()));
    QVERIFY(w.shell_view().triangles() > 100);
    auto* view = w.findChild<QWidget*>("shell_view");
    const QRect varea(view->mapTo(&w, QPoint(0, 0)), view->size());
    long blue = 0;
    for (int y = varea.top(); y <= varea.bottom(); y += 2)
      for (int x = varea.left(); x <= varea.right(); x += 2) {
        const QRgb p = shot.pixel(x, y);
        blue += qBlue(p) > qRed(p) + 60;
      }
    QVERIFY2(blue > 500, qPrintable(QString::number(blue)));
    // The preview renders it: moving the body out of the frame (both shapes 0.3 m along x)
    // changes the middle of the preview, where the camera looks at the cube.
    const QImage with_body = w.preview_image();
    const QRect middle(with_body.width() * 3 / 8, with_body.height() * 3 / 8, with_body.width() / 4,
                       with_body.height() / 4);
    w.modify([](ScenarioDocument& d) {
      d.set("shape.outer.center_m", std::array<double, 3>{0.3, 0.0, 0.0});
      d.set("shape.cavity.center_m", std::array<double, 3>{0.3, 0.0, 0.0});
    });
    QVERIFY2(w.check().ok(), w.check().message.c_str());
    QVERIFY(wait_for_full_size(w));
    QTRY_VERIFY_WITH_TIMEOUT(!w.renderer().busy(), 120000);
    const QImage without = w.preview_image();
    const double moved = mean_difference(with_body.copy(middle), without.copy(middle));
    QVERIFY2(moved > 10, qPrintable(QString::number(moved)));
  }

  // The Scenario tab of a grid scenario (issue 25 item 6) edits its [shape] and grid solver keys
  // instead of the 1D radii; the edits round-trip through the file, its comments kept; switching
  // the kind of a body or the solver's family is one edit.
  void theScenarioTabEditsAGridScenariosShape() {
    const fs::path source = fs::path(THAW_SOURCE_DIR) / "data/scenarios/hollow_cube.toml";
    MainWindow w{ScenarioDocument::load(source)};
    w.show();
    QVERIFY2(w.check().ok(), w.check().message.c_str());
    QVERIFY(w.select_tab("scenario"));
    auto* shell_form = w.findChild<QWidget*>("shell_form");
    auto* shape_form = w.findChild<QWidget*>("shape_form");
    QVERIFY(shell_form && shape_form);
    QVERIFY(shell_form->isHidden());  // no "sphere 0.02/0.03 m"
    QVERIFY(!shape_form->isHidden());
    auto combo = [&](const char* key) { return w.findChild<QComboBox*>(key)->currentText(); };
    auto text = [&](const char* key) { return w.findChild<QLineEdit*>(key)->text(); };
    auto enabled = [&](const char* key) {
      auto* f = w.findChild<QWidget*>(key);
      return f && f->isEnabled();
    };
    QCOMPARE(combo("simulation.geometry"), QString("3d"));
    QCOMPARE(combo("shape.outer.kind"), QString("box"));
    QCOMPARE(combo("shape.cavity.kind"), QString("box"));
    // The flow as the scenario has it (the solver's default when the file names none); then off.
    QCOMPARE(
        combo("simulation.flow"),
        QString(w.check().scenario->simulation.natural_convection ? "natural_convection" : "none"));
    QVERIFY2(w.apply_edit("simulation.flow", std::string("none")), w.check().message.c_str());
    QCOMPARE(combo("simulation.flow"), QString("none"));
    QCOMPARE(text("shape.outer.size_m.text"), QString("0.04, 0.04, 0.04"));
    // the solver's default cell, as the field prints it (10 significant digits)
    const double cell = thaw::sim::effective_cell_size_m(w.check().scenario->simulation);
    QVERIFY(std::abs(text("simulation.cell_size_m").toDouble() - cell) < 1e-9 * cell);
    QVERIFY(enabled("shape.outer.size_m"));
    QVERIFY(!enabled("shape.outer.radius_m"));
    // Typed sizes reach the parsed scenario and round-trip through the saved file.
    QVERIFY(w.document().layout_kept());
    type_into(w, "shape.outer.size_m", "0.05, 0.04, 0.045");
    QVERIFY(w.document().layout_kept());  // edited in place, the comments kept
    type_into(w, "simulation.cell_size_m", "0.001");
    QVERIFY(w.document().layout_kept());
    QVERIFY2(w.check().ok(), w.check().message.c_str());
    QCOMPARE(w.check().scenario->simulation.shape.outer.size_m,
             (std::array<double, 3>{0.05, 0.04, 0.045}));
    const fs::path file = temp_dir() / "hollow_cube_edited.toml";
    QVERIFY(w.save_file(file));
    const std::string saved = read_bytes(file);
    QVERIFY(saved.find("# The first report's object") != std::string::npos);
    QVERIFY(saved.find("cell_size_m = 0.001") != std::string::npos);
    MainWindow back{ScenarioDocument::load(file)};
    QVERIFY2(back.check().ok(), back.check().message.c_str());
    QCOMPARE(back.check().scenario->simulation_text, w.check().scenario->simulation_text);
    // A cavity turned into a sphere gets a radius; "none" removes it (solid ice).
    QVERIFY2(w.apply_edit("shape.cavity.kind", std::string("sphere")), w.check().message.c_str());
    QCOMPARE(w.check().scenario->simulation.shape.cavity->radius_m, 0.015);
    QVERIFY(enabled("shape.cavity.radius_m"));
    QVERIFY(!enabled("shape.cavity.size_m"));
    QVERIFY2(w.apply_edit("shape.cavity.kind", std::string("none")), w.check().message.c_str());
    QVERIFY(!w.check().scenario->simulation.shape.cavity);
    QVERIFY(!enabled("shape.cavity.center_m"));
    QVERIFY2(w.apply_edit("shape.cavity.kind", std::string("box")), w.check().message.c_str());
    QCOMPARE(w.check().scenario->simulation.shape.cavity->size_m,
             (std::array<double, 3>{0.03, 0.03, 0.03}));
    // Natural convection is one choice; the flow's rule on the cell shows under its field.
    QVERIFY(!w.apply_edit("simulation.flow", std::string("natural_convection")));
    QVERIFY(!w.field_problem("simulation.cell_size_m").isEmpty());
    QVERIFY2(w.apply_edit("simulation.cell_size_m", 0.0005), w.check().message.c_str());
    QVERIFY(w.check().scenario->simulation.natural_convection);
    // To the 1D solver and back: a hollow sphere is carried over as radii, and back as spheres.
    QVERIFY2(w.apply_edit("shape.cavity.kind", std::string("sphere")), w.check().message.c_str());
    // (a typical 1.5 cm sphere is no larger body than the cavity: the rule's message shows)
    QVERIFY(!w.apply_edit("shape.outer.kind", std::string("sphere")));
    QVERIFY2(w.apply_edit("shape.outer.radius_m", 0.03), w.check().message.c_str());
    QVERIFY2(w.apply_edit("simulation.geometry", std::string("sphere")), w.check().message.c_str());
    QVERIFY(!shell_form->isHidden());
    QVERIFY(shape_form->isHidden());
    QCOMPARE(w.check().scenario->simulation.outer_radius_m, 0.03);
    QCOMPARE(w.check().scenario->simulation.inner_radius_m, 0.015);
    QVERIFY2(w.apply_edit("simulation.geometry", std::string("axisymmetric")),
             w.check().message.c_str());
    QCOMPARE(w.check().scenario->simulation.shape.outer.radius_m, 0.03);
    QCOMPARE(w.check().scenario->simulation.shape.cavity->radius_m, 0.015);
    QVERIFY(shell_form->isHidden());
  }

  // A flow run's Simulation tab shows the largest speed in the water (issue 25 item 6): the
  // largest of the run's flow rows (summary.json's), and the slider's step's own.
  void aFlowRunShowsItsLargestSpeed() {
    MainWindow w{ScenarioDocument::load(fs::path(THAW_SOURCE_DIR) /
                                        "data/scenarios/hollow_sphere_flow.toml")};
    w.show();
    w.modify([](ScenarioDocument& d) {
      // 20 s (outputs at 0 and 20 s): the water is stirring by then (~2 mm/s), and the run and
      // its meshes stay well inside the test function's time on a loaded machine.
      d.set("simulation.duration_s", 20.0);
      d.set("simulation.output_interval_s", 20.0);
      d.set("film.frames", 2LL);
    });
    QVERIFY2(w.check().ok(), w.check().message.c_str());
    auto* speed = w.findChild<QLabel*>("flow_speed");
    QVERIFY(speed && speed->isHidden());
    QSignalSpy finished(&w, &MainWindow::simulationFinished);
    QVERIFY(w.start_simulation());
    QTRY_VERIFY_WITH_TIMEOUT(finished.count() == 1, 300000);
    const auto run = w.simulation_run();
    QVERIFY(run && !run->flow_records.empty());
    double largest = 0;
    for (const auto& f : run->flow_records) largest = std::max(largest, f[1]);
    QVERIFY(largest > 0);
    QVERIFY(!speed->isHidden());
    const QString shown = QString::number(largest * 1e3, 'f', 2) + " mm/s";
    QVERIFY2(speed->text().contains(shown), qPrintable(speed->text() + " / " + shown));
    QVERIFY2(speed->text().contains("at this step"), qPrintable(speed->text()));
    // A stale run (an edit of the simulation) hides it.
    QVERIFY(w.apply_edit("simulation.duration_s", 90.0));
    QVERIFY(speed->isHidden());
  }

  void screenshotOfTheDefaultHasThePanelsAndARender() {
    MainWindow w{ScenarioDocument()};
    w.show();
    const fs::path png = temp_dir() / "default.png";
    fs::remove(png);
    std::string problem = "not finished";
    thaw::gui::take_screenshot_when_ready(w, png, [&](const std::string& p) { problem = p; });
    QTRY_VERIFY_WITH_TIMEOUT(problem != "not finished", 300000);
    QCOMPARE(QString::fromStdString(problem), QString());
    QImage shot(QString::fromStdString(png.string()));
    QVERIFY(!shot.isNull());
    QCOMPARE(shot.size(), w.size());
    // The panels: the tabs are laid out, and the 3D view holds the shell.
    auto* tabs = w.findChild<QTabWidget*>("tabs");
    QVERIFY(tabs && tabs->count() >= 2 && tabs->isVisible());
    QVERIFY(w.shell_view().triangles() > 100);
    // The render: the preview label's area of the screenshot is not uniform.
    auto* preview = w.findChild<QLabel*>("preview");
    const QRect area(preview->mapTo(&w, QPoint(0, 0)), preview->size());
    QVERIFY2(grey_spread(shot, area) > 10, qPrintable(QString::number(grey_spread(shot, area))));
    // The 3D view: water blue (blue clearly above red) appears in its area.
    auto* view = w.findChild<QWidget*>("shell_view");
    const QRect varea(view->mapTo(&w, QPoint(0, 0)), view->size());
    long blue = 0;
    for (int y = varea.top(); y <= varea.bottom(); y += 2)
      for (int x = varea.left(); x <= varea.right(); x += 2) {
        const QRgb p = shot.pixel(x, y);
        blue += qBlue(p) > qRed(p) + 60;
      }
    QVERIFY2(blue > 500, qPrintable(QString::number(blue)));
    // ... and the scene around it: the default floor's red checker cells (red clearly above
    // blue), which the shell alone does not have.
    long red = 0;
    for (int y = varea.top(); y <= varea.bottom(); y += 2)
      for (int x = varea.left(); x <= varea.right(); x += 2) {
        const QRgb p = shot.pixel(x, y);
        red += qRed(p) > qBlue(p) + 60;
      }
    QVERIFY2(red > 2000, qPrintable(QString::number(red)));
    // What the display shows (the X server's pixels of the window, the view's own OpenGL child
    // window included): the water's blue in the view's area there too.
    const QImage screen = QGuiApplication::primaryScreen()->grabWindow(w.winId()).toImage();
    QCOMPARE(screen.size(), w.size());
    long shown = 0;
    for (int y = varea.top(); y <= varea.bottom(); y += 2)
      for (int x = varea.left(); x <= varea.right(); x += 2) {
        const QRgb p = screen.pixel(x, y);
        shown += qBlue(p) > qRed(p) + 60;
      }
    QVERIFY2(shown > 500, qPrintable(QString::number(shown)));
  }
};

int main(int argc, char** argv) {
  std::unique_ptr<thaw::inspect::DisplayLease> display;
  if (!thaw::inspect::display_available())
    display = std::make_unique<thaw::inspect::DisplayLease>("test_gui_window");
  QApplication app(argc, argv);
  TestMainWindow test;
  return QTest::qExec(&test, argc, argv);
}

#include "test_main_window.moc"
