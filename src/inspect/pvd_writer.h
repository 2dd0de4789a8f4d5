#pragma once
// ParaView time series: a .pvd collection (plain XML, written by hand) referencing one .vtp per
// step and surface, the inner (water|ice) and outer (ice|air) surfaces as separate parts, the
// timestep being the simulated time in seconds. The .vtp files are written into a staged folder
// as they are added, which replaces `<stem>_vtp/` by commit(), before the .pvd is written; so an
// interrupted or failed export (disk full) leaves neither a .pvd nor a partial folder of data
// sets. Needs no display.
#include <array>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "base/atomic_file.h"
#include "base/progress.h"
#include "base/work_farm.h"
#include "src/inspect/simulation_folder.h"
#include "src/inspect/triangle_mesh.h"

namespace thaw::inspect {

/// A named value per vertex, written as point data beside the normals (e.g. "temperature_c").
struct PointScalars {
  std::string name;
  std::vector<double> values;  ///< one per vertex of the mesh it goes with
};

/// The part numbers used in thaw's collections.
enum class SurfacePart { inner = 0, outer = 1 };

class PvdWriter {
 public:
  /// `pvd_path`: the collection file; the .vtp files go in the folder `<stem>_vtp/` beside it
  /// (staged until commit()). Throws thaw::UserError if that folder cannot be created.
  explicit PvdWriter(std::filesystem::path pvd_path);
  /// A writer of data sets into `write_dir`, the folder another process's PvdWriter for
  /// `pvd_path` has staged (the ranks of thaw run): write() only; that process records and
  /// commits.
  PvdWriter(std::filesystem::path pvd_path, std::filesystem::path write_dir);

  /// Writes step `step`'s `part` surface (nullptr: vanished, written as an empty data set so the
  /// part disappears at that time instead of ParaView holding the last surface). time_s: simulated
  /// time [s]. `scalars`: point data of `mesh` (see write_vtp). Re-adding a step's part replaces
  /// its entry.
  void add(long step, double time_s, SurfacePart part, const TriangleMesh* mesh,
           const std::vector<PointScalars>& scalars = {});
  /// add() in two halves for writers on several threads: write() writes the data set (safe
  /// concurrently for different steps or parts), record() references it (one thread at a time).
  void write(long step, SurfacePart part, const TriangleMesh* mesh,
             const std::vector<PointScalars>& scalars = {}) const;
  void record(long step, double time_s, SurfacePart part);

  /// Puts the data sets in place (`<stem>_vtp/`, replaced as a whole the first time) and writes the
  /// .pvd (atomically) referencing every data set added; throws thaw::UserError. Data sets added
  /// after a commit are written in place and need another commit.
  void commit();

  const std::filesystem::path& pvd_path() const { return m_pvd; }
  const std::filesystem::path& data_dir() const { return m_data_dir; }
  /// Where write() puts the data sets now: the staged folder until commit(), then data_dir().
  std::filesystem::path write_dir() const;
  /// Number of data sets referenced so far.
  std::size_t size() const { return m_entries.size(); }

 private:
  struct Entry {
    double time_s;
    int part;
    std::string file;  // relative to the .pvd's folder, '/'-separated
  };
  std::filesystem::path m_pvd, m_data_dir;
  std::filesystem::path m_foreign_dir;  ///< another process's staged folder (second constructor)
  std::optional<StagingDirectory> m_staging;  ///< until the first commit()
  std::vector<Entry> m_entries;
};

/// Unit normals at the vertices of `mesh`: the file's own (`vn`, by the corners that name them)
/// when it has them, else the area-weighted mean of the adjacent faces' normals (Gouraud's
/// vertex normal, each face weighted by its area through the unnormalised cross product).
std::vector<std::array<double, 3>> vertex_normals(const TriangleMesh& mesh);

/// Writes `mesh` as a VTK XML PolyData file atomically (arrays inline, zlib level 1), with the
/// point data "Normals" (vertex_normals, set as the data set's normals so ParaView shades with
/// them) when the mesh has triangles, and each of `scalars` as a point data array (the first set
/// as the active scalars, so ParaView colours by it). THAW_CHECK: one value per vertex.
void write_vtp(const std::filesystem::path& path, const TriangleMesh& mesh,
               const std::vector<PointScalars>& scalars = {});

/// Where step `step`'s surfaces are placed in the world [m] (added to every point); `thaw run`
/// passes the offset it rendered them at, so ParaView shows them where the film does.
using StepPlacement = std::function<std::array<double, 3>(long step)>;

/// Writes the collection for every meshed step of a simulation folder (see simulation_folder.h);
/// OBJs are validated as by inspect_obj. progress: (steps done, steps total). A grid run's step
/// with a field (SIMDIR/fields/step_NNNNNN.grid) gets the point data "temperature_c": the
/// material's temperature at each vertex (field_probe.h), sampled before the placement.
void write_pvd_series(const std::filesystem::path& simdir, const std::filesystem::path& out_pvd,
                      const ProgressCallback& progress = {}, const StepPlacement& placement = {});

/// The options of the second write_pvd_series, for a caller that places the surfaces by their
/// own shape and exports them elsewhere too (thaw run: the shell rests on the floor by its
/// lowest point; the OBJ sequence for Blender), reading each OBJ once.
struct PvdSeriesOptions {
  /// (steps done, steps total); called on any of the threads, never concurrently. May throw
  /// (an interrupt): the series then fails with that exception.
  ProgressCallback progress;
  /// Where a step's surfaces are placed, given its outer surface as read (nullptr: vanished);
  /// none: where they are. Called once per step, concurrently for different steps.
  std::function<std::array<double, 3>(const MeshedStep& step, const TriangleMesh* outer)> placement;
  /// Called with each surface as written to its .vtp (placed; nullptr: vanished), once per step
  /// and part, concurrently for different steps. May throw thaw::UserError (the series fails).
  std::function<void(const MeshedStep& step, SurfacePart part, const TriangleMesh* mesh)> surface;
  /// Steps written at once (OpenMP threads; <= 0: OpenMP's default). The files are the same for
  /// any number.
  int threads = 1;
  /// Several processes writing one series (thaw run under MPI; nullptr: this process alone).
  /// Every process calls write_pvd_series with the same arguments: the leader stages the data
  /// sets' folder and shares its path, the farm hands the steps out (each process writing its
  /// steps on `threads` threads), and the leader records and commits them. `progress` is called
  /// on the leader only, `placement` and `surface` wherever a step is written.
  WorkFarm* farm = nullptr;
};

/// Where `placement` put each step (by step number): nothing without a placement.
using StepOffsets = std::map<long, std::array<double, 3>>;

/// write_pvd_series with PvdSeriesOptions; returns the offset each step was placed at (with a
/// farm: every step's on the leader, nothing on the others). A failure (the first in step order)
/// is thrown after every step has been attempted; nothing is committed then. With a farm, a
/// failure to stage or to write a step is thrown on every process as it was (base/outcome.h),
/// and steps not yet begun are skipped.
StepOffsets write_pvd_series(const std::filesystem::path& simdir,
                             const std::filesystem::path& out_pvd, const PvdSeriesOptions& options);

}  // namespace thaw::inspect
