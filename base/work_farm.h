#pragma once
// Where the independent items of a piece of work are computed: on this process's threads
// (this_process_farm), or spread over the processes of a run that share one folder (thaw run's
// MPI ranks, src/pipeline/run_ranks.h). The algorithms that hand out items (the meshers, the
// inspect series, the render stage) see only this interface: nothing here knows about MPI, only
// "the leader and the others". A failing item's outcome (base/outcome.h) is carried back and
// thrown as it was on every process.
#include <functional>
#include <string>
#include <vector>

#include "base/outcome.h"

namespace thaw {

class WorkFarm {
 public:
  /// How items compare with the cost of handing one out.
  enum class Grain {
    /// many cheap items (surfaces, steps): handed out in chunks, each chunk on `threads` threads
    fine,
    /// few costly items (frames): one at a time to whichever process is free; each item uses the
    /// process's threads itself, so a process works on one at a time
    coarse,
  };

  virtual ~WorkFarm() = default;
  /// The process that gathers the results, writes manifests and commits (alone: this one).
  virtual bool leader() const { return true; }
  /// How many processes share the work (alone: 1).
  virtual int processes() const { return 1; }
  /// The leader's `text` on every process (what others pass is ignored).
  virtual std::string share(const std::string& text) { return text; }
  /// Calls work(k) once for each k in [0, n), somewhere, and returns on the leader the text each
  /// call returned, indexed by k (on other processes: n empty texts). On the leader, done() is
  /// called once per finished item, never concurrently. `threads` (fine grain): items at once on
  /// each process (<= 0: OpenMP's default). If work (or done) throws, items not yet begun are
  /// skipped and every process throws the first failure (on one process: the lowest item's) as
  /// it was (Outcome::rethrow); items finished before stay finished.
  virtual std::vector<std::string> run(long n, int threads,
                                       const std::function<std::string(long)>& work,
                                       const std::function<void()>& done,
                                       Grain grain = Grain::fine);
  /// The leader's outcome on every process: how a step that the leader alone ran ended.
  Outcome leaders_outcome(const Outcome& mine) { return Outcome::from_text(share(mine.to_text())); }
};

/// This process alone, on its threads: the farm used when none is given.
WorkFarm& this_process_farm();

}  // namespace thaw
