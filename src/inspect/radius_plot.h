#pragma once
// The first picture a user wants after a simulation: inner and outer radius against time (top)
// and the liquid and ice volumes against time (bottom), as a PNG chart drawn with VTK's charts
// (vtkChartXY). Units are chosen for readability (mm/cm/m, s/min/h) and printed on the axes.
// Rendering needs X: a DisplayLease (virtual_display.h) is taken. Output written atomically.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sim/format/interface_history.h"

namespace thaw::inspect {

struct PlotOptions {
  std::string title = "thaw: melting history";
  /// Geometry, for axis names and volume units (sphere when unknown).
  std::optional<sim::Geometry> geometry;
  int width_px = 1200, height_px = 1000;
};

/// Plots `rows` (at least one) into `out_png`. Throws thaw::UserError without an X display
/// (and no Xvfb) or when the PNG cannot be written.
void write_radius_plot(const std::vector<sim::InterfaceRecord>& rows,
                       const std::filesystem::path& out_png, const PlotOptions& options = {});

/// Reads SIMDIR/interfaces.csv (and summary.json for the geometry when present) and plots it.
void write_radius_plot(const std::filesystem::path& simdir, const std::filesystem::path& out_png);

}  // namespace thaw::inspect
