#pragma once
// The solver's output contract, shared with the mesher and the inspector (which may read
// sim/format, nothing else of sim): DIR/interfaces.csv, one row per output time, and the
// geometry fields of DIR/summary.json. Knows nothing of how the history was computed.
#include <filesystem>
#include <string>
#include <vector>

#include "sim/scenario/geometry.h"
#include "sim/scenario/interface_record.h"

namespace thaw::sim {

/// The exact header line (without newline) that interfaces.csv starts with.
extern const char* const kInterfacesCsvHeader;

/// Formats rows at 17 significant digits with kInterfacesCsvHeader.
std::string format_interfaces_csv(const std::vector<InterfaceRecord>& rows);
/// Writes DIR/interfaces.csv atomically.
void write_interfaces_csv(const std::filesystem::path& file,
                          const std::vector<InterfaceRecord>& rows);
/// Reads interfaces.csv; columns found by header name (extra columns ignored). Throws
/// thaw::UserError naming file, line and column for a missing file, bad header, unparsable,
/// NaN/infinite or negative value, inner > outer, or non-increasing time.
std::vector<InterfaceRecord> read_interfaces_csv(const std::filesystem::path& file);

/// What the mesher needs from DIR/summary.json ("parameters" object, see simulate docs).
struct ShellGeometry {
  Geometry geometry = Geometry::sphere;
  /// Cylinder only: length of the capsule's straight tube [m] (shell.length_m).
  double length_m = 0;
  /// Planar only: lateral size of the slab's flat faces [m] (shell.lateral_size_m).
  double lateral_size_m = 0;
  /// Planar only: true when the inner end is a symmetry mid-plane (the slab is mirrored about
  /// x = 0), false when it is a heated wall at x = 0.
  bool planar_symmetric = true;
};
/// Reads parameters.simulation.geometry, parameters.shell.length_m / lateral_size_m and
/// parameters.inner_boundary.kind from summary.json; throws thaw::UserError on problems.
ShellGeometry read_shell_geometry(const std::filesystem::path& summary_json);

}  // namespace thaw::sim
