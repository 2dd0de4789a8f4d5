#pragma once
// The Simulation panel's plot (QPainter): inner and outer radius [mm] above, water and ice volume
// [ml] below, against time [min], with a marker at the time slider's step. The same quantities
// as `thaw inspect`'s plot.png (src/inspect/radius_plot.h), drawn live in the window.
#include <QWidget>
#include <vector>

#include "sim/format/interface_history.h"

namespace thaw::gui {

class RadiusPlot : public QWidget {
  Q_OBJECT
 public:
  explicit RadiusPlot(QWidget* parent = nullptr);
  void set_rows(std::vector<sim::InterfaceRecord> rows);
  /// Marks time `t_s` (the slider's step); negative hides the marker.
  void set_marker(double t_s);
  QSize sizeHint() const override { return {360, 260}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  std::vector<sim::InterfaceRecord> m_rows;
  double m_marker_s = -1;
};

}  // namespace thaw::gui
