#include "src/gui/view_render_thread.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkLightKit.h>
#include <vtkNew.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkTexture.h>
#include <vtkUnsignedCharArray.h>

#include <sys/eventfd.h>
#include <unistd.h>

#include <QSocketNotifier>
#include <cstdint>
#include <cstring>
#include <memory>
#include <utility>

#include "base/check.h"
#include "src/gui/preview_renderer.h"

namespace thaw::gui {

/// The thread's VTK objects: made, used and destroyed on the render thread only.
struct ViewRenderThread::Scene {
  vtkSmartPointer<vtkRenderWindow> window;
  vtkSmartPointer<vtkRenderer> renderer;
  vtkSmartPointer<vtkTextActor> label;
  /// the actors in the renderer, in drawing order
  std::vector<vtkActor*> order;
  /// every actor drawn so far, kept until no one else holds it (then released here: sweep)
  std::vector<vtkSmartPointer<vtkActor>> known;
  /// and every texture (an actor drawn quick has none attached)
  std::vector<vtkSmartPointer<vtkTexture>> known_textures;

  void make(int width, int height);
  /// Makes the renderer show `frame`: its actors (place_actors), their look (apply_look), the
  /// label, the camera and the size.
  void apply(const ViewFrame& frame);
  /// The renderer's actors and their order as the frame's; the shell placed.
  void place_actors(const ViewFrame& frame);
  /// The quick look or the look at rest.
  void apply_look(const ViewFrame& frame);
  QImage draw(int width, int height);
  void sweep();
  void release_all();
};

void ViewRenderThread::Scene::make(int width, int height) {
  window = vtkSmartPointer<vtkRenderWindow>::New();
  window->SetOffScreenRendering(1);  // VTK's own frame buffer: read back, painted by Qt
  // No glXSwapBuffers after a draw: with Mesa's software driver it sends the hidden window's
  // pixels to the X server, which the GUI thread's requests then wait behind.
  window->SwapBuffersOff();
  window->SetAlphaBitPlanes(1);
  window->SetMultiSamples(0);
  window->SetSize(width, height);
  renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->GradientBackgroundOn();
  renderer->SetBackground(0.10, 0.11, 0.14);
  renderer->SetBackground2(0.30, 0.33, 0.40);
  // No depth peeling (thaw inspect's pictures use it): with software OpenGL (Mesa llvmpipe, as
  // under Xvfb) its passes made every redraw several times slower; the one translucent surface
  // over an opaque one blends acceptably in drawing order.
  renderer->AutomaticLightCreationOff();
  vtkNew<vtkLightKit> lights;
  lights->AddLightsToRenderer(renderer);
  label = vtkSmartPointer<vtkTextActor>::New();
  label->GetTextProperty()->SetFontSize(14);
  label->GetTextProperty()->SetColor(0.95, 0.96, 0.98);
  label->GetTextProperty()->SetBackgroundColor(0.10, 0.11, 0.14);  // legible over the floor
  label->GetTextProperty()->SetBackgroundOpacity(0.7);
  label->SetDisplayPosition(8, 8);
  renderer->AddViewProp(label);
  window->AddRenderer(renderer);
}

void ViewRenderThread::Scene::apply(const ViewFrame& frame) {
  place_actors(frame);
  apply_look(frame);
  if (frame.label != (label->GetInput() ? label->GetInput() : ""))
    label->SetInput(frame.label.c_str());
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(frame.camera.position.data());
  camera->SetFocalPoint(frame.camera.focal_point.data());
  camera->SetViewUp(frame.camera.view_up.data());
  camera->SetViewAngle(frame.camera.vertical_fov_deg);
  renderer->ResetCameraClippingRange();
  const int* size = window->GetSize();
  if (size[0] != frame.width || size[1] != frame.height) window->SetSize(frame.width, frame.height);
}

void ViewRenderThread::Scene::place_actors(const ViewFrame& frame) {
  // The actors in drawing order: the scene's, then the water, then the ice.
  std::vector<vtkActor*> wanted;
  for (const auto& a : frame.scene) wanted.push_back(a);
  for (const auto& p : frame.shell) wanted.push_back(p.actor);
  if (wanted != order) {
    for (vtkActor* a : order) renderer->RemoveViewProp(a);
    for (vtkActor* a : wanted) renderer->AddViewProp(a);
    order = wanted;
  }
  for (vtkActor* a : wanted) {
    bool seen = false;
    for (const auto& k : known) seen = seen || k.Get() == a;
    if (!seen) known.emplace_back(a);
  }
  for (const auto& t : frame.textures) {
    bool seen = !t;
    for (const auto& k : known_textures) seen = seen || k.Get() == t.Get();
    if (!seen) known_textures.push_back(t);
  }
  for (const auto& p : frame.shell) {
    const double* at = p.actor->GetPosition();
    if (at[0] != p.position[0] || at[1] != p.position[1] || at[2] != p.position[2])
      p.actor->SetPosition(p.position[0], p.position[1], p.position[2]);
  }
}

void ViewRenderThread::Scene::apply_look(const ViewFrame& frame) {
  // The quick look (ViewFrame::quick), or the look at rest: each changed only when it differs
  // (a property set again would mark the actor modified).
  if (frame.outer && frame.outer->GetProperty()->GetEdgeVisibility() != frame.edges)
    frame.outer->GetProperty()->SetEdgeVisibility(frame.edges);
  for (std::size_t k = 0; k < frame.scene.size() && k < frame.textures.size(); ++k) {
    vtkTexture* texture = frame.textures[k];
    if (!texture) continue;
    vtkActor* actor = frame.scene[k];
    vtkTexture* drawn = frame.quick ? nullptr : texture;
    if (actor->GetTexture() != drawn) actor->SetTexture(drawn);
    const std::array<double, 3> c =
        frame.quick ? frame.quick_colors[k] : std::array<double, 3>{1, 1, 1};
    const double* now = actor->GetProperty()->GetColor();
    if (now[0] != c[0] || now[1] != c[1] || now[2] != c[2])
      actor->GetProperty()->SetColor(c[0], c[1], c[2]);
  }
}

QImage ViewRenderThread::Scene::draw(int width, int height) {
  window->Render();
  vtkNew<vtkUnsignedCharArray> pixels;
  window->GetPixelData(0, 0, width - 1, height - 1, /*front=*/0, pixels, /*right=*/0);
  QImage image(width, height, QImage::Format_RGB888);
  if (pixels->GetNumberOfValues() < 3 * vtkIdType(width) * height) {
    image.fill(Qt::black);
    return image;
  }
  const unsigned char* data = pixels->GetPointer(0);
  for (int y = 0; y < height; ++y)  // OpenGL's rows bottom-up, QImage's top-down
    std::memcpy(image.scanLine(height - 1 - y), data + 3 * std::size_t(width) * y,
                3 * std::size_t(width));
  return image;
}

namespace {

/// Releases (in `window`'s context) and forgets the objects of `objects` that only it holds.
template <class T>
void release_unheld(std::vector<vtkSmartPointer<T>>& objects, vtkRenderWindow* window) {
  for (auto it = objects.begin(); it != objects.end();) {
    if ((*it)->GetReferenceCount() == 1) {
      (*it)->ReleaseGraphicsResources(window);
      it = objects.erase(it);
    } else {
      ++it;
    }
  }
}

}  // namespace

void ViewRenderThread::Scene::sweep() {
  // An actor only this list holds (its step or scene replaced, not in the renderer) is released
  // here, in the context that uploaded it: dropped elsewhere, its buffers would be freed on a
  // thread without that context.
  release_unheld(known, window);
  release_unheld(known_textures, window);
}

void ViewRenderThread::Scene::release_all() {
  if (!window) return;
  for (vtkActor* a : order) renderer->RemoveViewProp(a);
  order.clear();
  for (const auto& a : known) a->ReleaseGraphicsResources(window);
  known.clear();
  for (const auto& t : known_textures) t->ReleaseGraphicsResources(window);
  known_textures.clear();
  label->ReleaseGraphicsResources(window);
  window->Finalize();
}

ViewRenderThread::ViewRenderThread(QObject* parent) : QObject(parent) {
  m_event_fd = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  THAW_CHECK(m_event_fd >= 0, "eventfd for the 3D view's frames");
  m_notifier = new QSocketNotifier(m_event_fd, QSocketNotifier::Read, this);
  connect(m_notifier, &QSocketNotifier::activated, this, [this] { take_frame(); });
  m_thread = std::thread([this] { run(); });
}

ViewRenderThread::~ViewRenderThread() {
  m_stop = true;
  delete m_pending.exchange(new ViewFrame());  // wakes the thread
  m_pending.notify_one();
  m_thread.join();
  delete m_pending.exchange(nullptr);
  delete m_drawn_frame.exchange(nullptr);
  delete m_notifier;
  ::close(m_event_fd);
}

void ViewRenderThread::request(ViewFrame frame) {
  // The request the thread had not started (if any) is dropped here: its actors are either drawn
  // before (then the thread holds them too) or never drawn (no OpenGL resources to release).
  delete m_pending.exchange(new ViewFrame(std::move(frame)));
  m_pending.notify_one();
}

void ViewRenderThread::take_frame() {
  std::uint64_t count = 0;
  (void)!::read(m_event_fd, &count, sizeof count);
  const std::unique_ptr<Drawn> drawn(m_drawn_frame.exchange(nullptr));
  if (drawn) emit frameReady(drawn->image, drawn->serial);
}

void ViewRenderThread::run() {
  // Below the GUI thread, above the preview's renders (kPreviewNice): llvmpipe's rasterizer
  // threads, started with the OpenGL context made here, inherit it. Under load the GUI thread
  // then gets a core first whenever its event loop has work.
  lower_thread_priority(kViewNice);
  // The render window, its OpenGL context and a first (empty) draw at once, while the window is
  // still being built: their X requests (display connection, GLX, the hidden window) then do not
  // queue at the X server with those of the window's show() on the GUI thread.
  Scene scene;
  scene.make(64, 64);
  scene.window->Render();
  while (true) {
    m_pending.wait(nullptr);
    if (m_stop) break;
    std::unique_ptr<ViewFrame> frame(m_pending.exchange(nullptr));
    if (!frame || frame->width <= 0 || frame->height <= 0) continue;
    scene.apply(*frame);
    const QImage image = scene.draw(frame->width, frame->height);
    const auto serial = static_cast<quint64>(frame->serial);
    frame.reset();  // the actors it held: the sweep below may release them
    scene.sweep();
    ++m_drawn;
    // handed over: a frame the GUI thread had not taken yet is replaced
    delete m_drawn_frame.exchange(new Drawn{image, serial});
    const std::uint64_t one = 1;
    (void)!::write(m_event_fd, &one, sizeof one);
  }
  scene.release_all();
}

}  // namespace thaw::gui
