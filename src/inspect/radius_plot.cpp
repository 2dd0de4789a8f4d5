#include "src/inspect/radius_plot.h"

#include <vtkAxis.h>
#include <vtkBrush.h>
#include <vtkChartLegend.h>
#include <vtkChartMatrix.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>
#include <vtkVector.h>

#include <algorithm>
#include <cstdio>

#include "base/error.h"
#include "sim/format/interface_history.h"
#include "src/inspect/virtual_display.h"
#include "src/inspect/vtk_png.h"

namespace thaw::inspect {
namespace fs = std::filesystem;
namespace {

struct Unit {
  double scale;      // multiply SI values by this
  std::string name;  // printed in the axis title
};

/// Seconds up to 5 min, minutes up to 5 h, hours beyond.
Unit time_unit(double t_end_s) {
  if (t_end_s <= 300) return {1.0, "s"};
  if (t_end_s <= 5 * 3600) return {1.0 / 60, "min"};
  return {1.0 / 3600, "h"};
}

Unit length_unit(double max_m) {
  if (max_m < 0.1) return {1e3, "mm"};
  if (max_m < 1.0) return {1e2, "cm"};
  return {1.0, "m"};
}

/// Volume units by geometry: the columns hold m^3 (sphere), m^3 per metre of length (cylinder:
/// a cross-section area) or m^3 per m^2 of face (planar: a thickness).
Unit volume_unit(sim::Geometry g, double max_value) {
  switch (g) {
    case sim::Geometry::planar:
      return max_value < 0.1 ? Unit{1e3, "mm (volume per unit area)"}
                             : Unit{1.0, "m (volume per unit area)"};
    case sim::Geometry::cylinder:
      return max_value < 1e-2 ? Unit{1e4, "cm\u00b2 (volume per unit length)"}
                              : Unit{1.0, "m\u00b2 (volume per unit length)"};
    case sim::Geometry::sphere:
      break;
  }
  if (max_value < 1e-3) return {1e6, "cm\u00b3"};
  if (max_value < 1.0) return {1e3, "L"};
  return {1.0, "m\u00b3"};
}

void style_axis(vtkAxis* axis, const std::string& title) {
  axis->SetTitle(title);
  axis->GetTitleProperties()->SetFontSize(20);
  axis->GetTitleProperties()->SetBold(false);
  axis->GetLabelProperties()->SetFontSize(16);
  axis->GetGridPen()->SetColor(215, 215, 215);
}

vtkPlot* add_line(vtkChartXY* chart, vtkTable* table, int column, unsigned char r, unsigned char g,
                  unsigned char b, bool markers) {
  vtkPlot* line = chart->AddPlot(vtkChart::LINE);
  line->SetInputData(table, 0, column);
  line->SetColor(r, g, b, 255);
  line->SetWidth(3.0);
  if (auto* points = vtkPlotPoints::SafeDownCast(line))
    points->SetMarkerStyle(markers ? vtkPlotPoints::CIRCLE : vtkPlotPoints::NONE);
  return line;
}

void style_chart(vtkChartXY* chart, const std::string& title) {
  chart->SetTitle(title);
  chart->GetTitleProperties()->SetFontSize(24);
  chart->GetTitleProperties()->SetBold(true);
  chart->SetShowLegend(true);
  chart->GetLegend()->GetLabelProperties()->SetFontSize(18);
  chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
  chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
  chart->GetLegend()->GetBrush()->SetColor(255, 255, 255, 230);
}

/// The plot's units, chosen from the data's extent.
struct PlotUnits {
  Unit time, length, volume;
  double max_radius_m = 0, max_total_volume_m3 = 0;
};

PlotUnits plot_units(const std::vector<sim::InterfaceRecord>& rows, sim::Geometry geometry) {
  PlotUnits u;
  double max_v = 0;
  for (const auto& r : rows) {
    u.max_radius_m = std::max({u.max_radius_m, r.outer_radius_m, r.inner_radius_m});
    max_v = std::max({max_v, r.liquid_volume_m3, r.ice_volume_m3});
    u.max_total_volume_m3 = std::max(u.max_total_volume_m3, r.liquid_volume_m3 + r.ice_volume_m3);
  }
  u.time = time_unit(rows.back().time_s);
  u.length = length_unit(u.max_radius_m);
  u.volume = volume_unit(geometry, max_v);
  return u;
}

void add_column(vtkTable* table, const char* name) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  table->AddColumn(a);
}

/// The rows in display units: radii (time, inner, outer) and volumes (time, water, ice, total).
void fill_tables(const std::vector<sim::InterfaceRecord>& rows, const PlotUnits& u, bool planar,
                 vtkTable* radii, vtkTable* volumes) {
  add_column(radii, "time");
  add_column(radii, planar ? "melt front (water|ice)" : "inner radius (water|ice)");
  add_column(radii, planar ? "outer surface (ice|air)" : "outer radius (ice|air)");
  add_column(volumes, "time");
  add_column(volumes, "liquid water");
  add_column(volumes, "ice");
  add_column(volumes, "total");
  const auto n = static_cast<vtkIdType>(rows.size());
  radii->SetNumberOfRows(n);
  volumes->SetNumberOfRows(n);
  for (vtkIdType i = 0; i < n; ++i) {
    const sim::InterfaceRecord& r = rows[static_cast<std::size_t>(i)];
    const double t = r.time_s * u.time.scale;
    radii->SetValue(i, 0, t);
    radii->SetValue(i, 1, r.inner_radius_m * u.length.scale);
    radii->SetValue(i, 2, r.outer_radius_m * u.length.scale);
    volumes->SetValue(i, 0, t);
    volumes->SetValue(i, 1, r.liquid_volume_m3 * u.volume.scale);
    volumes->SetValue(i, 2, r.ice_volume_m3 * u.volume.scale);
    volumes->SetValue(i, 3, (r.liquid_volume_m3 + r.ice_volume_m3) * u.volume.scale);
  }
}

/// Fixed ranges: y from zero so the eye reads proportions, not just trends; x over the run.
void fix_ranges(vtkChartXY* chart, double y_max, double t0, double t1) {
  vtkAxis* y = chart->GetAxis(vtkAxis::LEFT);
  chart->RecalculateBounds();
  y->SetBehavior(vtkAxis::FIXED);
  y->SetRange(0.0, y_max > 0 ? 1.08 * y_max : 1.0);
  vtkAxis* x = chart->GetAxis(vtkAxis::BOTTOM);
  x->SetBehavior(vtkAxis::FIXED);
  x->SetRange(t0, t1 > t0 ? t1 : t0 + 1.0);
}

}  // namespace

void write_radius_plot(const std::vector<sim::InterfaceRecord>& rows, const fs::path& out_png,
                       const PlotOptions& options) {
  if (rows.empty()) throw UserError(out_png.string(), "", "nothing to plot: no rows");
  const sim::Geometry geometry = options.geometry.value_or(sim::Geometry::sphere);
  const bool planar = geometry == sim::Geometry::planar;
  const bool markers = rows.size() <= 40;  // few rows: show where the samples are
  const PlotUnits u = plot_units(rows, geometry);
  vtkNew<vtkTable> radii, volumes;
  fill_tables(rows, u, planar, radii, volumes);

  const DisplayLease display("--plot");
  vtkNew<vtkContextView> view;
  view->GetRenderWindow()->SetOffScreenRendering(1);
  view->GetRenderWindow()->SetSize(options.width_px, options.height_px);
  view->GetRenderWindow()->SetMultiSamples(0);
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);

  vtkNew<vtkChartMatrix> matrix;
  matrix->SetSize(vtkVector2i(1, 2));
  matrix->SetBorders(110, 70, 40, 30);
  matrix->SetGutter(vtkVector2f(30.0f, 110.0f));
  view->GetScene()->AddItem(matrix);
  auto* top = vtkChartXY::SafeDownCast(matrix->GetChart(vtkVector2i(0, 1)));
  auto* bottom = vtkChartXY::SafeDownCast(matrix->GetChart(vtkVector2i(0, 0)));
  if (top == nullptr || bottom == nullptr)
    throw std::logic_error("vtkChartMatrix gave no vtkChartXY");

  const std::string time_title = "time [" + u.time.name + "]";
  style_chart(top, options.title + (planar ? ": front positions" : ": interface radii"));
  add_line(top, radii, 2, 90, 160, 200, markers);  // outer: ice blue
  add_line(top, radii, 1, 20, 70, 170, markers);   // inner: water blue
  style_axis(top->GetAxis(vtkAxis::BOTTOM), time_title);
  style_axis(top->GetAxis(vtkAxis::LEFT),
             (planar ? "position [" : "radius [") + u.length.name + "]");

  style_chart(bottom, "Volumes");
  add_line(bottom, volumes, 3, 140, 140, 140, markers);  // total: grey
  add_line(bottom, volumes, 2, 90, 160, 200, markers);   // ice
  add_line(bottom, volumes, 1, 20, 70, 170, markers);    // water
  style_axis(bottom->GetAxis(vtkAxis::BOTTOM), time_title);
  style_axis(bottom->GetAxis(vtkAxis::LEFT), "volume [" + u.volume.name + "]");

  const double t0 = rows.front().time_s * u.time.scale, t1 = rows.back().time_s * u.time.scale;
  fix_ranges(top, u.max_radius_m * u.length.scale, t0, t1);
  fix_ranges(bottom, u.max_total_volume_m3 * u.volume.scale, t0, t1);
  save_png(view->GetRenderWindow(), out_png);
}

void write_radius_plot(const fs::path& simdir, const fs::path& out_png) {
  const std::vector<sim::InterfaceRecord> rows =
      sim::read_interfaces_csv(simdir / "interfaces.csv");
  PlotOptions options;
  std::error_code ec;
  // A grid run (fields/) has volume-equivalent radii: plotted as spheres (the default).
  if (!fs::is_directory(simdir / "fields", ec) && fs::exists(simdir / "summary.json", ec))
    options.geometry = sim::read_shell_geometry(simdir / "summary.json").geometry;
  fs::path name = fs::absolute(simdir).lexically_normal();
  if (name.filename().empty()) name = name.parent_path();
  options.title = name.filename().string();
  write_radius_plot(rows, out_png, options);
}

}  // namespace thaw::inspect
