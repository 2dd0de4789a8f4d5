#include "src/gui/shell_view.h"

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkImageData.h>
#include <vtkLightKit.h>
#include <vtkMapper.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkProp.h>
#include <vtkPropCollection.h>
#include <vtkProperty.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkTexture.h>
#include <vtkWindowToImageFilter.h>

#include <QVTKInteractor.h>
#include <QVTKOpenGLWindow.h>
#include <QApplication>
#include <QGuiApplication>
#include <QImage>
#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QTimer>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>

#include "src/inspect/surface_actor.h"

namespace thaw::gui {

/// What decides the shaders and pipeline state an actor is drawn with (see Staged in the
/// header): actors with equal looks draw with the programs the first of them compiled.
std::string look_of(vtkProp* prop) {
  auto* actor = vtkActor::SafeDownCast(prop);
  if (!actor) return prop->GetClassName();
  vtkProperty* p = actor->GetProperty();
  vtkPolyData* data = actor->GetMapper()
                          ? vtkPolyData::SafeDownCast(actor->GetMapper()->GetInputDataObject(0, 0))
                          : nullptr;
  char text[160];
  std::snprintf(text, sizeof text,
                "actor texture %d tcoords %d normals %d translucent %d edges %d interpolation %d "
                "culling %d unlit %d",
                actor->GetTexture() != nullptr, data && data->GetPointData()->GetTCoords(),
                data && data->GetPointData()->GetNormals(), p->GetOpacity() < 1.0,
                p->GetEdgeVisibility(), p->GetInterpolation(), p->GetBackfaceCulling(),
                p->GetDiffuse() == 0.0);
  return text;
}

namespace {

/// Whether Qt's platform can make an OpenGL context. Qt's platforms without a window system
/// (offscreen without GLX, minimal) cannot, and an OpenGL window exposed there crashes in Qt's
/// paint (Qt 5.15, QT_QPA_PLATFORM=offscreen without a display: a null context dereferenced in
/// QPaintDeviceWindow::exposeEvent). On the others (xcb) a context is assumed, as any Qt OpenGL
/// widget does, without the cost of making one here.
/// The view's plain background (its first paint, then the gradient's lower colour).
constexpr float kBackground[3] = {0.10f, 0.11f, 0.14f};

bool platform_has_opengl() {
  const QString platform = QGuiApplication::platformName();
  if (platform != "offscreen" && platform != "minimal") return true;
  QOpenGLContext probe;
  return probe.create();
}

}  // namespace

/// VTK's OpenGL window whose paints only clear to the view's plain background until the view's
/// first draw: the first paint makes the OpenGL context and sets VTK up, and a VTK frame would
/// also be blitted to the window in it, which llvmpipe does with a blit shader it compiles with
/// LLVM (20 ms of CPU, in every process). So the context comes in one event-loop turn, the first
/// frame in a later one (the view's first draw), its blit in the paint that frame requests.
class ViewWindow : public QVTKOpenGLWindow {
 public:
  ViewWindow(vtkGenericOpenGLRenderWindow* window, std::function<void()> first_paint)
      : QVTKOpenGLWindow(window), m_first_paint(std::move(first_paint)) {}
  /// The view draws from now on: paints show VTK's frames.
  void start_drawing() { m_drawing = true; }

 protected:
  void paintGL() override {
    if (m_drawing) return QVTKOpenGLWindow::paintGL();
    QOpenGLFunctions* f = context()->functions();
    f->glClearColor(kBackground[0], kBackground[1], kBackground[2], 1.0f);
    f->glClear(GL_COLOR_BUFFER_BIT);
    if (m_painted) return;
    m_painted = true;
    QTimer::singleShot(0, this, m_first_paint);
  }

 private:
  std::function<void()> m_first_paint;
  bool m_painted = false, m_drawing = false;
};

ShellView::ShellView(QWidget* parent) : QWidget(parent) {
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  window->SetAlphaBitPlanes(1);  // depth peeling for the translucent outer surface
  window->SetMultiSamples(0);
  // A draw's frame reaches the screen in the paint it requests (QWindow::requestUpdate), which
  // Qt 5 delays by QT_QPA_UPDATE_IDLE_TIME, 5 ms unless set: the view's frames are shown at
  // once, as a QOpenGLWidget's were (with the delay, a slider drag's next draw often came before
  // the last frame's paint and waited for its rasterization instead).
  if (!qEnvironmentVariableIsSet("QT_QPA_UPDATE_IDLE_TIME"))
    qputenv("QT_QPA_UPDATE_IDLE_TIME", "0");
  m_window = new ViewWindow(window, [this] { first_frame(); });
  m_window->setFormat(QVTKOpenGLWindow::defaultFormat());
  // As VTK's QVTKOpenGLStereoWidget embeds it: the container lets the window take the mouse, and
  // the window's events reach this widget too.
  QWidget* container = QWidget::createWindowContainer(m_window, this);
  container->setAttribute(Qt::WA_TransparentForMouseEvents);
  container->setMouseTracking(true);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(container);
  connect(m_window, &QVTKOpenGLWindow::windowEvent, this,
          [this](QEvent* e) { QApplication::sendEvent(this, e); });
  setMouseTracking(true);
  setFocusPolicy(Qt::StrongFocus);
  // Without OpenGL the view stays its plain container, never painted (warming_up() false).
  if (!platform_has_opengl()) container->hide();
  m_stage_timer = new QTimer(this);
  m_stage_timer->setSingleShot(true);
  m_stage_timer->setInterval(0);
  connect(m_stage_timer, &QTimer::timeout, this, [this] { advance(); });
  // The next warm-up turn after a draw waits for that draw's frame to reach the window (its
  // paint, which blits it), or kFrameWaitMs if none comes (a window not exposed): a new look's
  // draw and the previous frame's paint are never one turn.
  m_frame_timer = new QTimer(this);
  m_frame_timer->setSingleShot(true);
  m_frame_timer->setInterval(kFrameWaitMs);
  connect(m_frame_timer, &QTimer::timeout, this, [this] { next_turn(); });
  connect(m_window, &QOpenGLWindow::frameSwapped, this, [this] {
    ++m_frames_shown;
    if (m_frame_timer->isActive()) next_turn();
  });
  m_settle_timer = new QTimer(this);
  m_settle_timer->setSingleShot(true);
  m_settle_timer->setInterval(kSettleMs);
  connect(m_settle_timer, &QTimer::timeout, this, [this] {
    settle_now();
    draw();
  });
  m_renderer = vtkSmartPointer<vtkRenderer>::New();
  // The first draw (the OpenGL context, Qt's compositing) clears to the plain background; the
  // gradient and the label, each a shader of its own, come in the next turns (warm-up).
  stage("gradient background", [this] { m_renderer->GradientBackgroundOn(); });
  m_renderer->SetBackground(kBackground[0], kBackground[1], kBackground[2]);
  m_renderer->SetBackground2(0.30, 0.33, 0.40);
  // No depth peeling (thaw inspect's pictures use it): with software OpenGL (Mesa llvmpipe, as
  // under Xvfb) its passes made every redraw several times slower; the one translucent surface
  // over an opaque one blends acceptably in drawing order.
  m_renderer->AutomaticLightCreationOff();
  vtkNew<vtkLightKit> lights;
  lights->AddLightsToRenderer(m_renderer);
  m_label = vtkSmartPointer<vtkTextActor>::New();
  m_label->GetTextProperty()->SetFontSize(14);
  m_label->GetTextProperty()->SetColor(0.95, 0.96, 0.98);
  m_label->GetTextProperty()->SetBackgroundColor(0.10, 0.11, 0.14);  // legible over the floor
  m_label->GetTextProperty()->SetBackgroundOpacity(0.7);
  m_label->SetDisplayPosition(8, 8);
  add_prop(m_label);
  window->AddRenderer(m_renderer);
  setMinimumSize(240, 180);
  // An orbit, pan or zoom with the mouse starts and ends with Start/EndInteractionEvent on the
  // interactor: drawn quick while it lasts, then at rest, and the camera reported.
  vtkNew<vtkCallbackCommand> on_start;
  on_start->SetClientData(this);
  on_start->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
    auto* view = static_cast<ShellView*>(self);
    view->m_interacting = true;
    view->set_quick(true);
  });
  vtkNew<vtkCallbackCommand> on_end;
  on_end->SetClientData(this);
  on_end->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
    auto* view = static_cast<ShellView*>(self);
    view->m_interacting = false;
    view->settle();
    view->report_camera();
  });
  if (interactor()) {
    interactor()->AddObserver(vtkCommand::StartInteractionEvent, on_start);
    interactor()->AddObserver(vtkCommand::EndInteractionEvent, on_end);
  }
}

vtkRenderWindow* ShellView::renderWindow() const {
  return m_window->renderWindow();
}

QVTKInteractor* ShellView::interactor() const {
  return m_window->interactor();
}

void ShellView::paintEvent(QPaintEvent* event) {
  QWidget::paintEvent(event);
  // as VTK's QVTKOpenGLStereoWidget does: after a resize the embedded window may otherwise not
  // repaint although it got its resize event
  m_window->update();
}

ShellView::ViewCamera ShellView::camera() const {
  vtkCamera* c = m_renderer->GetActiveCamera();
  ViewCamera v{};
  c->GetPosition(v.position.data());
  c->GetFocalPoint(v.focal_point.data());
  c->GetViewUp(v.view_up.data());
  v.vertical_fov_deg = c->GetViewAngle();  // vertical unless UseHorizontalViewAngle
  return v;
}

void ShellView::set_camera(const ViewCamera& v) {
  vtkCamera* c = m_renderer->GetActiveCamera();
  c->SetPosition(v.position.data());
  c->SetFocalPoint(v.focal_point.data());
  c->SetViewUp(v.view_up.data());
  c->SetViewAngle(v.vertical_fov_deg);
  m_renderer->ResetCameraClippingRange();
  draw();
}

void ShellView::report_camera() {
  emit cameraMoved();
}

bool ShellView::edges_shown() const {
  return m_outer && m_outer->GetProperty()->GetEdgeVisibility();
}

void ShellView::set_quick(bool quick) {
  if (quick) m_settle_pending = false, m_settle_timer->stop();  // moving again
  m_quick = quick;
  if (m_outer) m_outer->GetProperty()->SetEdgeVisibility(!quick);  // the look of surface_actor.h
  // A textured actor (the floor's checker) is drawn in its texture's mean colour while quick:
  // llvmpipe's texture sampling was most of a draw's CPU time.
  for (std::size_t k = 0; k < m_scene.size(); ++k) {
    if (!m_scene_textures[k]) continue;
    m_scene[k]->SetTexture(quick ? nullptr : m_scene_textures[k].Get());
    const std::array<double, 3> c = quick ? m_quick_colors[k] : std::array<double, 3>{1, 1, 1};
    m_scene[k]->GetProperty()->SetColor(c[0], c[1], c[2]);
  }
}

void ShellView::settle() {
  if (!m_quick) return;
  // The draw at rest (edges, the mipmapped floor: llvmpipe's dearest draw) waits a little, the
  // view kept quick meanwhile (also for the interactor's own draw as a drag ends): the scene of
  // the new camera or step, which the window requests now, usually comes within that and is
  // drawn at rest once (set_scene), not twice.
  m_settle_pending = true;
  m_settle_timer->start();
}

void ShellView::settle_now() {
  if (!m_settle_pending) return;
  m_settle_pending = false;
  m_settle_timer->stop();
  set_quick(false);
}

void ShellView::set_scene(const SceneProps& props) {
  bool changed = m_settle_pending;  // the draw at rest that settle() deferred
  settle_now();
  if (props.key != m_scene_key) {
    for (const auto& a : m_scene) remove_prop(a);
    m_scene = props.actors;
    m_scene_textures = props.textures;
    m_quick_colors = props.quick_colors;
    set_quick(m_quick);  // before they are added: their look decides when
    for (const auto& a : m_scene) add_prop(a);
    m_scene_key = props.key;
    m_scene_objects = props.objects;
    m_scene_lights = props.lights;
    changed = true;
  }
  const ViewCamera now = camera();
  const render::CameraDescription& c = props.camera;
  auto near = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    double d = 0, n = 0;
    for (int k = 0; k < 3; ++k) d += std::abs(a[k] - b[k]), n += std::abs(a[k]) + std::abs(b[k]);
    return d <= 1e-9 * std::max(1.0, n);
  };
  // The view's own camera written back (an orbit) comes back unchanged: nothing to do then; and
  // the mouse's camera is not taken away while it drags (its end writes it back).
  const bool same = near(now.position, c.position) && near(now.focal_point, c.look_at) &&
                    near(now.view_up, c.up) &&
                    std::abs(now.vertical_fov_deg - c.vertical_fov_deg) <= 1e-9;
  if (!m_interacting && (!m_scene_camera || !same)) {
    vtkCamera* cam = m_renderer->GetActiveCamera();
    cam->SetPosition(c.position.data());
    cam->SetFocalPoint(c.look_at.data());
    cam->SetViewUp(c.up.data());
    cam->SetViewAngle(c.vertical_fov_deg);
    m_scene_camera = true;
    changed = true;
  }
  if (!changed) return;
  m_renderer->ResetCameraClippingRange();
  draw();
}

void ShellView::show_step(const ShellStep& step, const std::array<double, 3>& offset, bool frame,
                          bool moving) {
  if (m_outer) remove_prop(m_outer);
  if (m_inner) remove_prop(m_inner);
  m_outer = m_inner = nullptr;
  m_triangles = 0;
  // Opaque water first, then the translucent ice. The step's actors were built with their
  // normals off the GUI thread (shell_step.h); each keeps its uploaded triangles, so scrubbing
  // back over a step only draws.
  if (step.inner_actor && !step.inner_view.triangles.empty()) {
    m_inner = step.inner_actor;
    m_inner->SetPosition(offset[0], offset[1], offset[2]);
    m_triangles += static_cast<long>(step.inner_view.triangles.size());
  }
  if (step.outer_actor && !step.outer_view.triangles.empty()) {
    m_outer = step.outer_actor;
    m_outer->SetPosition(offset[0], offset[1], offset[2]);
    m_triangles += static_cast<long>(step.outer_view.triangles.size());
  }
  set_quick(moving || m_quick);
  if (m_inner) add_prop(m_inner);
  if (m_outer) add_prop(m_outer);
  char text[160];
  std::snprintf(text, sizeof text, "t = %.0f s   water radius %.1f mm   ice radius %.1f mm%s",
                step.row.time_s, 1e3 * step.row.inner_radius_m, 1e3 * step.row.outer_radius_m,
                m_triangles == 0 ? "   (no surface)" : "");
  m_label->SetInput(text);
  if (frame && !m_scene_camera) {
    vtkCamera* camera = m_renderer->GetActiveCamera();
    camera->SetPosition(offset[0] + 0.55, offset[1] + 0.38, offset[2] + 0.75);  // oblique, y up
    camera->SetFocalPoint(offset[0], offset[1], offset[2]);
    camera->SetViewUp(0, 1, 0);
    camera->SetViewAngle(30);
    m_renderer->ResetCamera();
  } else {
    m_renderer->ResetCameraClippingRange();
  }
  draw();
}

std::size_t ShellView::add_catalog(const SceneProps& catalog) {
  // One actor of each look not drawn yet (the others would only cost drawing time).
  const std::size_t first = m_catalog.size();
  std::set<std::string> added = m_looks;
  auto add = [&](const vtkSmartPointer<vtkActor>& actor) {
    if (!added.insert(look_of(actor)).second) return;
    m_catalog.push_back(actor);
    add_prop(actor);
  };
  for (std::size_t k = 0; k < catalog.actors.size(); ++k) {
    add(catalog.actors[k]);
    if (!catalog.textures[k]) continue;
    // the same actor drawn quick (set_quick): its texture off
    auto quick = vtkSmartPointer<vtkActor>::New();
    quick->ShallowCopy(catalog.actors[k]);
    quick->SetTexture(nullptr);
    add(quick);
  }
  draw();
  return m_catalog.size() - first;
}

void ShellView::first_frame() {
  if (m_painted) return;
  m_painted = true;  // the context exists: the warm-up's turns may begin
  if (!m_staged.empty() && !m_held) m_stage_timer->start();
}

QImage ShellView::image() {
  if (!m_painted) return {};
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(renderWindow());
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();  // VTK's own frame buffer, drawn again now
  grab->ShouldRerenderOn();
  grab->Update();
  vtkImageData* data = grab->GetOutput();
  int size[3];
  data->GetDimensions(size);
  QImage image(size[0], size[1], QImage::Format_RGB888);
  const auto* pixels = static_cast<const unsigned char*>(data->GetScalarPointer());
  for (int y = 0; y < size[1]; ++y)  // OpenGL's rows bottom-up, QImage's top-down
    std::memcpy(image.scanLine(size[1] - 1 - y), pixels + 3 * std::size_t(size[0]) * y,
                3 * std::size_t(size[0]));
  return image;
}

void ShellView::hold() {
  m_held = true;
}

void ShellView::release() {
  if (!m_held) return;
  m_held = false;
  if (!m_staged.empty() && m_painted) m_stage_timer->start();
}

std::size_t ShellView::drawn_props() const {
  return static_cast<std::size_t>(m_renderer->GetViewProps()->GetNumberOfItems());
}

void ShellView::add_prop(vtkProp* prop) {
  stage(
      look_of(prop), [this, prop] { m_renderer->AddViewProp(prop); }, prop);
  // A mipmapped texture (the floor's checker) is a turn of its own: its trilinear sampling is a
  // shader variant of its own for llvmpipe (its levels come made: mipmapped_texture.h; with
  // glGenerateMipmap that turn cost 50-60 ms of CPU). It is drawn bilinear first, mipmapped a
  // turn later.
  auto* actor = vtkActor::SafeDownCast(prop);
  vtkTexture* texture = actor ? actor->GetTexture() : nullptr;
  if (texture && texture->GetMipmap() && m_looks.count("mipmapped texture") == 0) {
    texture->MipmapOff();
    vtkSmartPointer<vtkTexture> keep = texture;
    // (if the actor is removed before that turn, its texture is mipmapped for a later return)
    stage(
        "mipmapped texture", [keep] { keep->MipmapOn(); }, prop, /*apply_when_removed=*/true);
  }
}

void ShellView::stage(const std::string& look, std::function<void()> apply, vtkProp* prop,
                      bool apply_when_removed) {
  const bool known = m_looks.count(look) > 0;
  if (known || (m_painted && !m_held && m_new_looks == 0 && m_staged.empty())) {
    if (!known) m_looks.insert(look), ++m_new_looks;
    apply();
    return;
  }
  m_staged.push_back({look, prop, std::move(apply), apply_when_removed});
  if (!m_painted || m_held || m_frame_timer->isActive()) return;
  // A new look applied since the last draw waits for its draw (the caller's, which starts the
  // frame timer) and that draw's frame: a turn started here drew again in the next event-loop
  // turn, before that frame's paint (two draws, 100-150 ms, in one GUI-thread block when an edit
  // brought two new looks). The frame timer stands in if no draw comes.
  if (m_new_looks > 0)
    m_frame_timer->start();
  else
    m_stage_timer->start();
}

void ShellView::remove_prop(vtkProp* prop) {
  m_renderer->RemoveViewProp(prop);
  for (auto it = m_staged.begin(); it != m_staged.end();) {
    if (it->prop.Get() != prop) {
      ++it;
      continue;
    }
    if (it->apply_when_removed) it->apply();
    it = m_staged.erase(it);
  }
}

void ShellView::draw() {
  m_most_new_looks = std::max(m_most_new_looks, m_new_looks);
  m_new_looks = 0;
  m_frames_at_draw = m_frames_shown;
  m_since_draw.start();
  if (m_painted) m_window->start_drawing();  // (before the first paint VTK cannot draw yet)
  renderWindow()->Render();
  if (!m_staged.empty() && m_painted && !m_held) m_frame_timer->start();  // then next_turn()
}

void ShellView::next_turn() {
  m_frame_timer->stop();
  m_stage_timer->start();
}

void ShellView::advance() {
  if (m_held) return;
  if (m_frames_shown == m_frames_at_draw && m_since_draw.isValid() &&
      m_since_draw.elapsed() < kFrameWaitMs)
    ++m_early_turns;
  while (!m_staged.empty()) {
    Staged& next = m_staged.front();
    const bool known = m_looks.count(next.look) > 0;
    if (!known && m_new_looks > 0) break;
    if (!known) m_looks.insert(next.look), ++m_new_looks;
    std::function<void()> apply = std::move(next.apply);
    m_staged.pop_front();
    apply();
  }
  draw();
}

}  // namespace thaw::gui
