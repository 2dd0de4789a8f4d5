#include "src/inspect/screenshot.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCoordinate.h>
#include <vtkLightKit.h>
#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <tuple>

#include "base/error.h"
#include "base/obj_reader.h"
#include "base/progress.h"
#include "src/inspect/simulation_folder.h"
#include "src/inspect/surface_actor.h"
#include "src/inspect/virtual_display.h"
#include "src/inspect/vtk_png.h"
#include "src/inspect/vtk_polydata.h"

namespace thaw::inspect {
namespace fs = std::filesystem;
namespace {

vtkNew<vtkTextActor> text(const std::string& s, int size, const double rgb[3], bool bold) {
  vtkNew<vtkTextActor> t;
  t->SetInput(s.c_str());
  vtkTextProperty* p = t->GetTextProperty();
  p->SetFontSize(size);
  p->SetColor(rgb[0], rgb[1], rgb[2]);
  p->SetBold(bold);
  p->SetFontFamilyToArial();
  return t;
}

/// Puts a 2D actor at (x, y) in its renderer's viewport, 0..1 each way (display positions would
/// be window pixels, outside every viewport but the first).
void place(vtkTextActor* actor, double x, double y) {
  actor->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  actor->GetPositionCoordinate()->SetValue(x, y);
}

/// Colour key at the bottom right of `renderer` for the roles present in `panels`.
void add_legend(vtkRenderer* renderer, const std::vector<ScreenshotPanel>& panels, int font_px,
                int viewport_px) {
  bool has_inner = false, has_outer = false;
  for (const ScreenshotPanel& p : panels)
    for (const SceneSurface& s : p.surfaces) {
      has_inner |= s.role == SurfaceRole::inner;
      has_outer |= s.role == SurfaceRole::outer;
    }
  // Lighter than the surface colours: those are too dark to read as text on the background.
  const double inner_rgb[3] = {0.45, 0.68, 1.0}, outer_rgb[3] = {0.85, 0.94, 1.0};
  double y = 0.03;
  for (const auto& [present, name, rgb] :
       {std::tuple{has_outer, "outer: ice|air (translucent)", outer_rgb},
        std::tuple{has_inner, "inner: water|ice", inner_rgb}}) {
    if (!present) continue;
    auto t = text(name, font_px, rgb, true);
    t->GetTextProperty()->SetJustificationToRight();
    place(t, 0.98, y);
    renderer->AddActor2D(t);
    y += 1.6 * font_px / viewport_px;
  }
}

/// Centre and radius of a sphere about the box centre holding every vertex of every panel.
struct Framing {
  double center[3] = {0.5, 0.5, 0.5};
  double radius = 1.0;
};

Framing frame_all(const std::vector<ScreenshotPanel>& panels) {
  double lo[3], hi[3];
  std::fill(lo, lo + 3, std::numeric_limits<double>::infinity());
  std::fill(hi, hi + 3, -std::numeric_limits<double>::infinity());
  bool any = false;
  for (const ScreenshotPanel& p : panels)
    for (const SceneSurface& s : p.surfaces)
      for (const auto& v : s.mesh.vertices) {
        any = true;
        for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], v[c]), hi[c] = std::max(hi[c], v[c]);
      }
  Framing f;
  if (!any) return f;
  for (int c = 0; c < 3; ++c) f.center[c] = 0.5 * (lo[c] + hi[c]);
  // A sphere rather than the box: frames any orientation of the view.
  double radius = 0;
  for (const ScreenshotPanel& p : panels)
    for (const SceneSurface& s : p.surfaces)
      for (const auto& v : s.mesh.vertices) {
        const double d[3] = {v[0] - f.center[0], v[1] - f.center[1], v[2] - f.center[2]};
        radius = std::max(radius, std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
      }
  if (radius > 0) f.radius = radius;
  return f;
}

/// One camera for every panel, framed on the union of all surfaces, so sizes compare directly.
void aim_camera(vtkCamera* camera, const Framing& f) {
  camera->SetFocalPoint(f.center);
  // An oblique view from above and in front: shows depth without hiding the inner surface.
  const double dir[3] = {0.55, -0.75, 0.38};
  const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  const double view_angle = 30.0;
  // Distance at which the bounding sphere just fits the view angle, plus a margin for labels.
  const double distance = 1.15 * f.radius / std::sin(0.5 * view_angle * M_PI / 180.0);
  camera->SetPosition(f.center[0] + distance * dir[0] / len, f.center[1] + distance * dir[1] / len,
                      f.center[2] + distance * dir[2] / len);
  camera->SetViewUp(0, 0, 1);
  camera->SetViewAngle(view_angle);
  camera->SetClippingRange(std::max(1e-6, distance - 2 * f.radius), distance + 2 * f.radius);
}

const double kTextRgb[3] = {0.95, 0.96, 0.98};
const double kDimRgb[3] = {0.70, 0.74, 0.80};

/// Panel i's renderer: its surfaces (opaque first), its label, the legend on the last panel.
vtkSmartPointer<vtkRenderer> panel_renderer(const std::vector<ScreenshotPanel>& panels,
                                            std::size_t i, vtkCamera* camera, int panel_px,
                                            double top, bool edges) {
  const double n = static_cast<double>(panels.size());
  auto renderer = vtkSmartPointer<vtkRenderer>::New();
  renderer->SetViewport(static_cast<double>(i) / n, 0.0, static_cast<double>(i + 1) / n, top);
  renderer->GradientBackgroundOn();
  renderer->SetBackground(0.10, 0.11, 0.14);
  renderer->SetBackground2(0.30, 0.33, 0.40);
  renderer->SetUseDepthPeeling(1);
  renderer->SetMaximumNumberOfPeels(12);
  renderer->SetOcclusionRatio(0.0);
  renderer->SetUseFXAA(true);
  renderer->SetActiveCamera(camera);
  renderer->AutomaticLightCreationOff();
  vtkNew<vtkLightKit> lights;
  lights->AddLightsToRenderer(renderer);
  // Opaque surfaces first, then translucent ones (depth peeling sorts them anyway).
  std::vector<const SceneSurface*> order;
  for (const SceneSurface& s : panels[i].surfaces) order.push_back(&s);
  std::stable_sort(order.begin(), order.end(), [](const SceneSurface* a, const SceneSurface* b) {
    return (a->role == SurfaceRole::outer) < (b->role == SurfaceRole::outer);
  });
  for (const SceneSurface* s : order)
    if (!s->mesh.triangles.empty()) renderer->AddActor(surface_actor(s->mesh, s->role, edges));
  if (!panels[i].label.empty()) {
    auto label = text(panels[i].label, std::max(12, panel_px / 36), kTextRgb, false);
    label->GetTextProperty()->SetVerticalJustificationToTop();
    place(label, 0.02, 0.98);
    renderer->AddActor2D(label);
  }
  if (panels[i].surfaces.empty()) {
    auto gone = text("(no surface left)", std::max(12, panel_px / 30), kDimRgb, false);
    gone->GetTextProperty()->SetJustificationToCentered();
    place(gone, 0.5, 0.5);
    renderer->AddActor2D(gone);
  }
  if (i + 1 == panels.size()) add_legend(renderer, panels, std::max(12, panel_px / 34), panel_px);
  return renderer;
}

/// The title band across the top of the window.
vtkSmartPointer<vtkRenderer> title_band(const std::string& title, int title_px, double top) {
  auto band = vtkSmartPointer<vtkRenderer>::New();
  band->SetViewport(0.0, top, 1.0, 1.0);
  band->SetBackground(0.06, 0.07, 0.09);
  auto label = text(title, std::max(14, title_px / 2), kTextRgb, true);
  label->GetTextProperty()->SetVerticalJustificationToCentered();
  place(label, 0.01, 0.5);
  band->AddActor2D(label);
  return band;
}

}  // namespace

void write_screenshot(const std::vector<ScreenshotPanel>& panels, const fs::path& out_png,
                      const ScreenshotOptions& options) {
  if (panels.empty()) throw UserError(out_png.string(), "", "nothing to draw");
  const DisplayLease display("--screenshot");

  const int n = static_cast<int>(panels.size());
  const int panel = std::max(64, options.panel_size_px);
  const int title_px = options.title.empty() ? 0 : std::max(36, panel / 12);
  const int width = panel * n, height = panel + title_px;

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(width, height);
  window->SetAlphaBitPlanes(1);  // depth peeling for the translucent outer surface
  window->SetMultiSamples(0);
  window->SetWindowName("thaw inspect");

  vtkNew<vtkCamera> camera;
  aim_camera(camera, frame_all(panels));
  const double top = static_cast<double>(panel) / height;
  for (std::size_t i = 0; i < panels.size(); ++i)
    window->AddRenderer(panel_renderer(panels, i, camera, panel, top, options.edges));
  if (title_px > 0) window->AddRenderer(title_band(options.title, title_px, top));
  save_png(window, out_png);
}

void write_obj_screenshot(const fs::path& obj, const fs::path& out_png) {
  ScreenshotPanel panel;
  panel.surfaces.push_back({meshio::read_obj(obj), SurfaceRole::single});
  ScreenshotOptions options;
  options.title = obj.filename().string();
  const auto& m = panel.surfaces.front().mesh;
  panel.label = std::to_string(m.vertices.size()) + " vertices, " +
                std::to_string(m.triangles.size()) + " triangles";
  write_screenshot({panel}, out_png, options);
}

void write_simulation_screenshot(const fs::path& simdir, const fs::path& out_png,
                                 std::optional<long> step) {
  const SimulationFolder folder = read_simulation_folder(simdir);
  if (!folder.meshed || folder.steps.empty())
    throw UserError((simdir / "mesh" / "manifest.json").string(), "",
                    "no meshed steps: mesh the simulation first (thaw mesh)");
  std::vector<std::size_t> picks;
  if (step) {
    for (std::size_t k = 0; k < folder.steps.size(); ++k)
      if (folder.steps[k].step == *step) picks.push_back(k);
    if (picks.empty())
      throw UserError(simdir.string(), "--step",
                      "step " + std::to_string(*step) + " is not meshed");
  } else {
    // Spread over the steps that still have a surface: a last step where everything has melted
    // would only show an empty panel.
    std::vector<std::size_t> candidates;
    for (std::size_t k = 0; k < folder.steps.size(); ++k)
      if (folder.steps[k].inner || folder.steps[k].outer) candidates.push_back(k);
    if (candidates.empty()) candidates.push_back(folder.steps.size() - 1);
    const std::size_t count = std::min<std::size_t>(4, candidates.size());
    for (std::size_t i = 0; i < count; ++i)
      picks.push_back(candidates[count == 1 ? 0 : i * (candidates.size() - 1) / (count - 1)]);
  }
  std::vector<ScreenshotPanel> panels;
  const double length_scale = folder.steps.front().outer_radius_m < 0.1 ? 1e3 : 1.0;
  const char* length_unit = length_scale == 1e3 ? "mm" : "m";
  for (const std::size_t k : picks) {
    const MeshedStep& s = folder.steps[k];
    ScreenshotPanel p;
    char label[256];
    std::snprintf(label, sizeof label, "step %ld   t = %s\ninner %.3g %s   outer %.3g %s", s.step,
                  ProgressReporter::format_duration(s.time_s).c_str(),
                  s.inner_radius_m * length_scale, length_unit, s.outer_radius_m * length_scale,
                  length_unit);
    p.label = label;
    if (s.inner) p.surfaces.push_back({meshio::read_obj(*s.inner), SurfaceRole::inner});
    if (s.outer) p.surfaces.push_back({meshio::read_obj(*s.outer), SurfaceRole::outer});
    panels.push_back(std::move(p));
  }
  ScreenshotOptions options;
  fs::path name = fs::absolute(simdir).lexically_normal();
  if (name.filename().empty()) name = name.parent_path();
  options.title = name.filename().string();
  write_screenshot(panels, out_png, options);
}

}  // namespace thaw::inspect
