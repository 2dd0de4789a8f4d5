#include "src/gui/shell_view.h"

#include <vtkActor.h>
#include <vtkTexture.h>

#include <QMouseEvent>
#include <QPainter>
#include <QTimer>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "src/gui/view_render_thread.h"
#include "src/inspect/virtual_display.h"

namespace thaw::gui {
namespace {

/// The view's plain background (before its first frame), the gradient's lower colour.
const QColor kBackground = QColor::fromRgbF(0.10, 0.11, 0.14);

/// The box about `mesh`'s vertices moved by `offset`, merged into `box`.
void grow(std::array<double, 6>& box, const inspect::TriangleMesh& mesh,
          const std::array<double, 3>& offset) {
  for (const auto& v : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      box[2 * k] = std::min(box[2 * k], v[k] + offset[k]);
      box[2 * k + 1] = std::max(box[2 * k + 1], v[k] + offset[k]);
    }
}

/// The mean edge length of `mesh`'s triangles [m] (0 without triangles).
double mean_edge_length(const inspect::TriangleMesh& mesh) {
  double sum = 0;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const auto& a = mesh.vertices[static_cast<std::size_t>(t[k])];
      const auto& b = mesh.vertices[static_cast<std::size_t>(t[(k + 1) % 3])];
      sum += std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
    }
  return mesh.triangles.empty() ? 0 : sum / (3.0 * static_cast<double>(mesh.triangles.size()));
}

}  // namespace

bool ShellView::edges_shown() const {
  if (!m_outer || m_quick || m_edge_length_m <= 0) return false;
  // The edge's size on the screen at the shell's distance: the view's height in pixels spans
  // 2 d tan(fov / 2) there.
  const auto& p = m_camera.position;
  const double d = std::hypot(p[0] - m_offset[0], p[1] - m_offset[1], p[2] - m_offset[2]);
  const double span_m =
      2.0 * d * std::tan(0.5 * m_camera.vertical_fov_deg * 3.14159265358979 / 180);
  return span_m > 0 && m_edge_length_m / span_m * height() >= kEdgeMinPx;
}

ShellView::ShellView(QWidget* parent) : QWidget(parent) {
  setAttribute(Qt::WA_OpaquePaintEvent);  // paintEvent covers every pixel
  setFocusPolicy(Qt::StrongFocus);
  setMinimumSize(240, 180);
  // VTK draws through X (GLX): without a display (Qt's offscreen platform alone) the view stays
  // its plain background; the rest of the window works.
  if (inspect::display_available()) {
    m_render = new ViewRenderThread(this);
    connect(m_render, &ViewRenderThread::frameReady, this, &ShellView::on_frame);
  }
  m_settle_timer = new QTimer(this);
  m_settle_timer->setSingleShot(true);
  m_settle_timer->setInterval(kSettleMs);
  connect(m_settle_timer, &QTimer::timeout, this, [this] {
    settle_now();
    draw();
  });
}

ShellView::~ShellView() {
  delete m_render;  // joins the render thread before the actors it draws go
  m_render = nullptr;
}

void ShellView::draw() {
  if (!m_render) return;
  ViewFrame frame;
  frame.scene = m_scene;
  frame.textures = m_scene_textures;
  frame.quick_colors = m_quick_colors;
  // Opaque water first, then the translucent ice.
  if (m_inner) frame.shell.push_back({m_inner, m_offset});
  if (m_outer) frame.shell.push_back({m_outer, m_offset});
  frame.outer = m_outer;
  frame.quick = m_quick;
  frame.edges = edges_shown();
  frame.label = m_label;
  frame.camera = m_camera;
  const qreal ratio = devicePixelRatioF();
  frame.width = std::max(1, static_cast<int>(std::lround(width() * ratio)));
  frame.height = std::max(1, static_cast<int>(std::lround(height() * ratio)));
  frame.serial = ++m_requested;
  m_render->request(std::move(frame));
}

void ShellView::on_frame(const QImage& image, quint64 serial) {
  if (serial <= m_received) return;
  m_received = serial;
  m_frame = image;
  m_frame.setDevicePixelRatio(devicePixelRatioF());
  // Painted at once (a few ms of copying on the raster backing store): frames_shown() counts
  // what reached the screen.
  repaint();
}

void ShellView::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  if (m_frame.isNull()) {
    painter.fillRect(rect(), kBackground);
    return;
  }
  // While the widget is resized the last frame is stretched until the new size's arrives.
  painter.drawImage(rect(), m_frame);
  if (m_painted != m_received) m_painted = m_received, ++m_frames_shown;
}

void ShellView::resizeEvent(QResizeEvent* event) {
  QWidget::resizeEvent(event);
  // Also the first layout's: the render thread makes its OpenGL context and draws the plain
  // gradient while the initial shell is still being meshed.
  draw();
}

void ShellView::set_camera(const ViewCamera& camera) {
  m_camera = camera;
  draw();
}

void ShellView::begin_interaction() {
  m_interacting = true;
  set_quick(true);
}

void ShellView::end_interaction() {
  m_interacting = false;
  settle();
  report_camera();
}

void ShellView::report_camera() {
  emit cameraMoved();
}

void ShellView::mousePressEvent(QMouseEvent* event) {
  if (m_button != Qt::NoButton) return;
  m_button = event->button();
  m_last = event->pos();
  begin_interaction();
}

void ShellView::mouseMoveEvent(QMouseEvent* event) {
  if (m_button == Qt::NoButton) return;
  const QPoint d = event->pos() - m_last;
  m_last = event->pos();
  const double w = std::max(1, width()), h = std::max(1, height());
  // VTK's trackball camera (vtkInteractorStyleTrackballCamera, motion factor 10): left drags
  // rotate (200 degrees across the view), shift-left or middle drags pan (the scene follows the
  // mouse), right drags zoom (1.1 to the power of 20 view heights).
  const bool pan_drag = m_button == Qt::MiddleButton ||
                        (m_button == Qt::LeftButton && (event->modifiers() & Qt::ShiftModifier));
  if (pan_drag)
    m_camera = pan(m_camera, -d.x() / h, d.y() / h);
  else if (m_button == Qt::LeftButton)
    m_camera = orbit(m_camera, -200.0 * d.x() / w, 200.0 * d.y() / h);
  else if (m_button == Qt::RightButton)
    m_camera = dolly(m_camera, std::pow(1.1, -20.0 * d.y() / h));
  else
    return;
  draw();
}

void ShellView::mouseReleaseEvent(QMouseEvent* event) {
  if (event->button() != m_button) return;
  m_button = Qt::NoButton;
  end_interaction();
}

void ShellView::wheelEvent(QWheelEvent* event) {
  // VTK's: 1.1 squared per notch (120 eighths of a degree), forward closer.
  const double notches = event->angleDelta().y() / 120.0;
  if (notches == 0 || m_button != Qt::NoButton) return;
  begin_interaction();
  m_camera = dolly(m_camera, std::pow(1.1, 2.0 * notches));
  draw();
  end_interaction();
}

void ShellView::set_quick(bool quick) {
  if (quick) m_settle_pending = false, m_settle_timer->stop();  // moving again
  m_quick = quick;
}

void ShellView::settle() {
  if (!m_quick) return;
  // The draw at rest (edges, the mipmapped floor: llvmpipe's dearest draw) waits a little, the
  // view kept quick meanwhile: the scene of the new camera or step, which the window requests
  // now, usually comes within that and is drawn at rest once (set_scene), not twice.
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
    m_scene = props.actors;
    m_scene_textures = props.textures;
    m_quick_colors = props.quick_colors;
    m_scene_key = props.key;
    m_scene_objects = props.objects;
    m_scene_lights = props.lights;
    changed = true;
  }
  const render::CameraDescription& c = props.camera;
  auto near = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    double d = 0, n = 0;
    for (int k = 0; k < 3; ++k) d += std::abs(a[k] - b[k]), n += std::abs(a[k]) + std::abs(b[k]);
    return d <= 1e-9 * std::max(1.0, n);
  };
  // The view's own camera written back (an orbit) comes back unchanged: nothing to do then; and
  // the mouse's camera is not taken away while it drags (its end writes it back).
  const bool same = near(m_camera.position, c.position) && near(m_camera.focal_point, c.look_at) &&
                    near(m_camera.view_up, c.up) &&
                    std::abs(m_camera.vertical_fov_deg - c.vertical_fov_deg) <= 1e-9;
  if (!m_interacting && (!m_scene_camera || !same)) {
    m_camera = {c.position, c.look_at, c.up, c.vertical_fov_deg};
    m_scene_camera = true;
    changed = true;
  }
  if (changed) draw();
}

void ShellView::show_step(const ShellStep& step, const std::array<double, 3>& offset, bool frame,
                          bool moving) {
  m_outer = m_inner = nullptr;
  m_triangles = 0;
  // The step's actors were built with their normals off the GUI thread (shell_step.h); each
  // keeps its uploaded triangles in the render thread's context, so scrubbing back over a step
  // only draws.
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::array<double, 6> box{inf, -inf, inf, -inf, inf, -inf};
  if (step.inner_actor && !step.inner_view.triangles.empty()) {
    m_inner = step.inner_actor;
    m_triangles += static_cast<long>(step.inner_view.triangles.size());
    grow(box, step.inner_view, offset);
  }
  if (step.outer_actor && !step.outer_view.triangles.empty()) {
    m_outer = step.outer_actor;
    m_triangles += static_cast<long>(step.outer_view.triangles.size());
    m_edge_length_m = mean_edge_length(step.outer_view);
    grow(box, step.outer_view, offset);
  }
  m_offset = offset;
  set_quick(moving || m_quick);
  char text[160];
  std::snprintf(text, sizeof text, "t = %.0f s   water radius %.1f mm   ice radius %.1f mm%s",
                step.row.time_s, 1e3 * step.row.inner_radius_m, 1e3 * step.row.outer_radius_m,
                m_triangles == 0 ? "   (no surface)" : "");
  m_label = text;
  if (frame && !m_scene_camera) {
    // oblique, y up, the shell filling the view (as vtkRenderer::ResetCamera frames it)
    m_camera = {{offset[0] + 0.55, offset[1] + 0.38, offset[2] + 0.75}, offset, {0, 1, 0}, 30};
    if (box[0] <= box[1])
      m_camera = frame_bounds(m_camera, box,
                              static_cast<double>(std::max(1, width())) / std::max(1, height()));
  }
  draw();
}

std::size_t ShellView::drawn_props() const {
  return m_scene.size() + (m_inner ? 1 : 0) + (m_outer ? 1 : 0) + 1;  // + the label
}

}  // namespace thaw::gui
