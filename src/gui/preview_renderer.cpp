#include "src/gui/preview_renderer.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>

#include "base/error.h"
#include "base/interrupt.h"
#include "render/image/image_io.h"
#include "render/integrator/whitted.h"
#include "render/scene/scene.h"
#include "src/gui/film_runner.h"

namespace thaw::gui {

QImage to_qimage(const render::Image& image, double exposure) {
  const float scale = static_cast<float>(std::exp2(exposure));
  QImage q(image.width(), image.height(), QImage::Format_RGB888);
  for (int y = 0; y < image.height(); ++y) {
    uchar* line = q.scanLine(y);
    for (int x = 0; x < image.width(); ++x) {
      const render::Rgb& p = image.at(x, y);
      line[3 * x] = render::to_srgb8(p.r, scale);
      line[3 * x + 1] = render::to_srgb8(p.g, scale);
      line[3 * x + 2] = render::to_srgb8(p.b, scale);
    }
  }
  return q;
}

PreviewRenderer::PreviewRenderer(QObject* parent) : QObject(parent) {
  m_thread = std::thread([this] { loop(); });
}

PreviewRenderer::~PreviewRenderer() {
  {
    std::lock_guard lock(m_mutex);
    m_quit = true;
    m_cancel = true;
  }
  m_wake.notify_all();
  m_thread.join();
}

std::uint64_t PreviewRenderer::request(PreviewRequest request) {
  std::uint64_t serial = 0;
  {
    std::lock_guard lock(m_mutex);
    m_pending = std::move(request);
    m_requested_at = std::chrono::steady_clock::now();
    serial = ++m_serial;
    m_cancel = true;  // the pass in flight stops at its next tile
  }
  m_wake.notify_all();
  return serial;
}

void PreviewRenderer::cancel() {
  std::lock_guard lock(m_mutex);
  m_pending.reset();
  m_cancel = true;
}

std::shared_ptr<const ShellStep> PreviewRenderer::initial_shell() const {
  std::lock_guard lock(m_mutex);
  return m_initial;
}

std::shared_ptr<const SceneProps> PreviewRenderer::scene_props() const {
  std::lock_guard lock(m_mutex);
  return m_props;
}

bool PreviewRenderer::busy() const {
  std::lock_guard lock(m_mutex);
  return m_pending.has_value() || m_rendering;
}

void lower_thread_priority(int nice) {
  // This thread and the OpenMP workers it starts (Linux threads inherit it). Best effort.
  (void)::setpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()), nice);
}

void PreviewRenderer::loop() {
  // Below the GUI thread and the 3D view's render thread (view_render_thread.h, with llvmpipe's
  // rasterizer threads): the render threads (OpenMP, started from here, inherit it) take the cores
  // only when the window does not need them. Under Linux's autogroup scheduling (one group per
  // session) this only orders the threads of this program: other programs' share is unchanged.
  lower_thread_priority(kPreviewNice);
  for (;;) {
    PreviewRequest request;
    std::chrono::steady_clock::time_point start;
    std::uint64_t serial = 0;
    {
      std::unique_lock lock(m_mutex);
      m_wake.wait(lock, [this] { return m_quit || m_pending.has_value(); });
      if (m_quit) return;
      request = std::move(*m_pending);
      m_pending.reset();
      start = m_requested_at;
      serial = m_serial;
      m_cancel = false;
      m_rendering = true;
    }
    try {
      serve(request, start, serial);
    } catch (const UserError& e) {
      emit failed(QString::fromStdString(e.what()));
    } catch (const std::exception& e) {
      emit failed(QString::fromStdString(std::string("internal error: ") + e.what()));
    }
    std::lock_guard lock(m_mutex);
    m_rendering = false;
  }
}

void PreviewRenderer::serve(const PreviewRequest& request,
                            std::chrono::steady_clock::time_point start, std::uint64_t serial) {
  std::shared_ptr<const ShellStep> step = request.step;
  if (!step) {
    // The initial shell depends on the simulation's and the mesher's keys only.
    const std::string key = request.scenario.simulation_text + "\n" + request.scenario.mesh_text;
    std::shared_ptr<const ShellStep> cached;
    {
      std::lock_guard lock(m_mutex);
      if (m_initial && m_initial_key == key) cached = m_initial;
    }
    if (!cached) {
      cached = std::make_shared<const ShellStep>(gui::initial_shell(request.scenario));
      {
        std::lock_guard lock(m_mutex);
        m_initial = cached;
        m_initial_key = key;
      }
      emit shellReady();
    }
    step = cached;
  }
  const auto passes = preview_passes(request.width, request.height, request.samples);
  for (std::size_t i = 0; i < passes.size();) {
    if (m_cancel) {  // replaced between two passes (e.g. while the 3D view's actors were made)
      ++m_abandoned;
      return;
    }
    const render::SceneDescription desc =
        preview_scene(request.scenario, *step, request.camera_rows, passes[i]);
    const render::Scene scene = render::build_scene(desc);
    render::RenderOptions options;
    options.cancel = &m_cancel;
    const std::uint64_t interrupts = FilmRunner::interrupts_started();
    const render::RenderResult result = render::render(scene, options);
    if (m_cancel) {  // incomplete: a newer request replaces it
      ++m_abandoned;
      return;
    }
    if (interrupt_requested() || FilmRunner::interrupts_started() != interrupts) {
      // A film's cancel raised the process-wide interrupt meanwhile: tiles may have been
      // skipped. Redo the pass once it is lowered (when the film's run has stopped).
      while (interrupt_requested() && !m_cancel)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      continue;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    emit imageReady(to_qimage(result.image, request.scenario.scene.image.exposure),
                    static_cast<int>(i), static_cast<int>(passes.size()), seconds, serial);
    if (i == 0) update_scene_props(desc, *step, serial);
    ++i;
  }
}

void PreviewRenderer::update_scene_props(const render::SceneDescription& desc,
                                         const ShellStep& step, std::uint64_t serial) {
  const std::vector<const render::TriangleMesh*> shell{step.outer.get(), step.inner.get()};
  std::shared_ptr<const SceneProps> last = scene_props();
  auto props = std::make_shared<SceneProps>();
  if (last && last->key == scene_props_key(desc, shell)) {
    *props = *last;  // the same actors: only the camera and the serial are new
    props->camera = desc.camera;
  } else {
    *props = make_scene_props(desc, shell, last.get());
  }
  props->serial = serial;
  {
    std::lock_guard lock(m_mutex);
    m_props = std::move(props);
  }
  emit sceneReady(serial);
}

}  // namespace thaw::gui
