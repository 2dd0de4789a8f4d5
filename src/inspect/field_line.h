#pragma once
// `thaw inspect SIMDIR --over-line "x0,y0,z0;x1,y1,z1" --samples N [--step K] --csv` (ParaView's
// Plot Over Line): a grid run's fields (sim/format/grid_field_file.h) sampled at N evenly spaced
// points of a segment, interpolated linearly between the cell centres (trilinear in 3D, bilinear
// in (r, y) for an axisymmetric field), as CSV. Positions are in the scenario's coordinates; an
// axisymmetric field is revolved about the y axis (r = hypot(x, z): on the line z = 0, x >= 0, x
// is the radius), its radial velocity turned into (u_x, u_z). Knows nothing of VTK.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sim/format/grid_field_file.h"

namespace thaw::inspect {

using Point3 = std::array<double, 3>;

/// One sample of the fields: position [m], temperature [C], liquid water volume fraction [0, 1]
/// and the water's velocity [m/s] (zero from a run without flow).
struct LineSample {
  Point3 position_m{0, 0, 0};
  double temperature_c = 0, liquid_fraction = 0;
  Point3 velocity_m_s{0, 0, 0};
};

/// The CSV's header line (no newline).
constexpr const char* kLineCsvHeader =
    "x_m,y_m,z_m,temperature_c,liquid_fraction,ux_m_s,uy_m_s,uz_m_s";

/// "x0,y0,z0;x1,y1,z1" as its two end points; a thaw::UserError("", "--over-line", problem)
/// for anything else (count of numbers, not a number, not finite).
std::array<Point3, 2> parse_line_ends(const std::string& text);

/// The fields at `point_m`, linear between the centres of the cells around it; between the
/// outermost centres and the grid's border the outermost value is held. On the axis of an
/// axisymmetric field (r below half a cell) the values are held and the radial velocity goes
/// linearly to 0 (the field's symmetry). Throws UserError("", "--over-line", ...) for a point
/// outside the grid's box.
LineSample sample_field(const sim::GridField& field, const Point3& point_m);

/// `samples` (>= 2) evenly spaced points from `a` to `b`, both included: a + (b - a) s / (N - 1).
std::vector<LineSample> sample_over_line(const sim::GridField& field, const Point3& a,
                                         const Point3& b, long samples);

/// The header and one line per sample, each number the shortest text of its double.
std::string format_line_csv(const std::vector<LineSample>& samples);

/// SIMDIR's field file of step `step` (fields/step_NNNNNN.grid), or its last step's; a run
/// folder's (DIR/sim/fields) too. UserError naming SIMDIR (and --step) when there is none.
std::filesystem::path field_file_of_step(const std::filesystem::path& simdir,
                                         std::optional<long> step);

}  // namespace thaw::inspect
