#pragma once
// One output time of an axisymmetric or 3D run: cell-centred fields on a uniform grid of cubic
// cells, as the grid solver produces them. sim/format/grid_field_file.h reads and writes it
// (DIR/fields/step_NNNNNN.grid). Knows nothing of files.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace thaw::sim {

/// One output time of an axisymmetric or 3D run, cell-centred on a uniform grid of cubic cells.
struct GridField {
  enum class Geometry { axisymmetric, cartesian3d };
  Geometry geometry = Geometry::cartesian3d;
  /// cells per axis: cartesian3d {nx, ny, nz} (y vertical); axisymmetric {nr, ny, 1} (r = radius
  /// from the vertical y axis)
  std::array<int, 3> cells{0, 0, 0};
  /// position of the lower corner of cell (0,0,0) [m] (axisymmetric: {0 (axis), y0, 0})
  std::array<double, 3> origin_m{0, 0, 0};
  /// cell edge [m]
  double spacing_m = 0;
  double time_s = 0;
  /// per cell, index i + cells[0]*(j + cells[1]*k): temperature [C], ice volume fraction [0,1],
  /// liquid water volume fraction [0,1] (the rest is air / outside)
  std::vector<float> temperature_c, ice_fraction, water_fraction;
  /// With flow ([simulation] flow = "natural_convection"): the water's velocity [m/s] at each
  /// cell centre, three floats per cell at 3 * index(i, j, k): (u_x, u_y, u_z); axisymmetric:
  /// (u_r, u_y, 0). Empty for a run without flow (and in files written before it was kept).
  std::vector<float> velocity_m_s;

  /// cells[0] * cells[1] * cells[2].
  std::size_t cell_count() const;
  /// The field carries a velocity (velocity_m_s not empty).
  bool has_velocity() const { return !velocity_m_s.empty(); }
  /// Flat index of cell (i, j, k).
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(cells[0]) *
               (static_cast<std::size_t>(j) + static_cast<std::size_t>(cells[1]) * k);
  }
};

/// The bounds of a field's header that thaw can have written, and that its readers and meshers
/// rely on: a cell edge from 1 nm (a continuum temperature field has no meaning on molecular
/// cells) to 100 m (the largest body the scenario rules accept, sim/scenario/scenario_rules.cpp),
/// and the whole grid within 1 km of the coordinates' origin (ten of the largest bodies). Outside
/// them the cell corners overflow or collapse onto each other in double precision (a spacing of
/// 1e300 m or an origin of 1e308 m made the mesher divide by zero, read out of bounds or allocate
/// without end).
constexpr double kMinFieldSpacingM = 1e-9;
constexpr double kMaxFieldSpacingM = 100.0;
constexpr double kMaxFieldCoordinateM = 1000.0;

/// What is wrong with a field's header: the header field ("cells", "origin_m", "spacing_m",
/// "time_s") and the problem, with the offending value.
struct GridFieldProblem {
  std::string field;
  std::string problem;
};

/// The first problem of `f`'s geometry (cells, origin, spacing, time) against the bounds above;
/// nullopt when a reader or mesher can use it. Does not look at the cell values.
std::optional<GridFieldProblem> find_header_problem(const GridField& f);

/// "axisymmetric" | "cartesian3d".
const char* to_string(GridField::Geometry geometry);

}  // namespace thaw::sim
