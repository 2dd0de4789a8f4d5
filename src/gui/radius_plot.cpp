#include "src/gui/radius_plot.h"

#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <functional>

namespace thaw::gui {
namespace {

/// One panel: curves of `values` (one getter per curve) against time, in `area`.
void draw_panel(
    QPainter& p, const QRectF& area, const std::vector<sim::InterfaceRecord>& rows,
    const std::vector<std::pair<std::function<double(const sim::InterfaceRecord&)>, QColor>>&
        curves,
    const QString& title, double marker_s) {
  p.setPen(QColor(90, 90, 100));
  p.drawRect(area);
  p.setPen(Qt::black);
  p.drawText(area.adjusted(6, 4, 0, 0), Qt::AlignLeft | Qt::AlignTop, title);
  if (rows.size() < 2) return;
  const double t0 = rows.front().time_s, t1 = std::max(rows.back().time_s, t0 + 1e-9);
  double vmax = 0;
  for (const auto& r : rows)
    for (const auto& c : curves) vmax = std::max(vmax, c.first(r));
  if (vmax <= 0) vmax = 1;
  vmax *= 1.1;
  auto X = [&](double t) { return area.left() + (t - t0) / (t1 - t0) * area.width(); };
  auto Y = [&](double v) { return area.bottom() - v / vmax * area.height(); };
  for (const auto& [value, colour] : curves) {
    QPainterPath path;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const QPointF q(X(rows[i].time_s), Y(value(rows[i])));
      if (i == 0)
        path.moveTo(q);
      else
        path.lineTo(q);
    }
    p.setPen(QPen(colour, 2));
    p.drawPath(path);
  }
  p.setPen(QColor(60, 60, 60));
  p.drawText(area.adjusted(0, 0, -4, -2), Qt::AlignRight | Qt::AlignTop,
             QString("max %1").arg(vmax / 1.1, 0, 'g', 3));
  p.drawText(area.adjusted(4, 0, 0, -2), Qt::AlignLeft | Qt::AlignBottom,
             QString("%1 min").arg(t0 / 60, 0, 'f', 0));
  p.drawText(area.adjusted(0, 0, -4, -2), Qt::AlignRight | Qt::AlignBottom,
             QString("%1 min").arg(t1 / 60, 0, 'f', 1));
  if (marker_s >= 0) {
    p.setPen(QPen(QColor(200, 60, 40), 1, Qt::DashLine));
    p.drawLine(QPointF(X(marker_s), area.top()), QPointF(X(marker_s), area.bottom()));
  }
}

}  // namespace

RadiusPlot::RadiusPlot(QWidget* parent) : QWidget(parent) {
  setMinimumHeight(200);
}

void RadiusPlot::set_rows(std::vector<sim::InterfaceRecord> rows) {
  m_rows = std::move(rows);
  update();
}

void RadiusPlot::set_marker(double t_s) {
  m_marker_s = t_s;
  update();
}

void RadiusPlot::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing);
  p.fillRect(rect(), Qt::white);
  const QRectF all = QRectF(rect()).adjusted(8, 8, -8, -8);
  const double h = (all.height() - 8) / 2;
  const QColor water(40, 105, 205), ice(120, 170, 210);
  draw_panel(p, QRectF(all.left(), all.top(), all.width(), h), m_rows,
             {{[](const sim::InterfaceRecord& r) { return 1e3 * r.inner_radius_m; }, water},
              {[](const sim::InterfaceRecord& r) { return 1e3 * r.outer_radius_m; }, ice}},
             "radius [mm]: water|ice (blue), ice|air (light)", m_marker_s);
  draw_panel(p, QRectF(all.left(), all.top() + h + 8, all.width(), h), m_rows,
             {{[](const sim::InterfaceRecord& r) { return 1e6 * r.liquid_volume_m3; }, water},
              {[](const sim::InterfaceRecord& r) { return 1e6 * r.ice_volume_m3; }, ice}},
             "volume [ml]: water (blue), ice (light)", m_marker_s);
}

}  // namespace thaw::gui
