#pragma once
// Where the independent pieces of a meshing run (distinct surfaces, grid steps) are computed: by
// default on this process's OpenMP threads; `thaw run` under MPI passes a farm that spreads them
// over the ranks sharing the simulation folder (src/pipeline). The meshers see only this
// interface: nothing here knows about MPI or processes beyond "the leader and the others".
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "base/atomic_file.h"

namespace thaw::mesh {

class MeshFarm {
 public:
  virtual ~MeshFarm() = default;
  /// The process that writes the manifest and commits the output folder (with one process: it).
  virtual bool leader() const { return true; }
  /// The leader's `text` on every process (what others pass is ignored).
  virtual std::string share(const std::string& text) { return text; }
  /// How many processes share the work (with one process: 1).
  virtual int processes() const { return 1; }
  /// Calls work(k) exactly once for each k in [0, n), somewhere, and returns on the leader the
  /// text each call returned, indexed by k (on other processes: n empty texts). On the leader,
  /// done() is called once per finished item, never concurrently. Here: `threads` OpenMP threads
  /// (<= 0: OpenMP's default), dynamic one item at a time. `work` must not throw (report failures
  /// in its text) and is called concurrently.
  virtual std::vector<std::string> run(long n, int threads,
                                       const std::function<std::string(long)>& work,
                                       const std::function<void()>& done);
};

/// The leader stages `final_dir` into `staging`; every process gets the staged folder's path. A
/// failure to stage is thrown on every process (the leader's own UserError there), so that no
/// process waits for a leader that has given up.
std::filesystem::path stage_on_leader(MeshFarm& farm, std::optional<StagingDirectory>& staging,
                                      const std::filesystem::path& final_dir);

/// This process's threads: the farm used when none is given.
MeshFarm& this_process_farm();

}  // namespace thaw::mesh
