#pragma once
// The processes sharing one `thaw run`: a single process, or the ranks of an MPI job
// (run_ranks_mpi.cpp, built with THAW_MPI). They are the run's work farm (base/work_farm.h): the
// stages, the meshers and the inspect series hand their items to it and never see MPI. Rank 0,
// the leader, simulates, keeps run_manifest.json and makes the film; items go to whichever rank
// asks next. Failures travel between ranks as outcomes (base/outcome.h), never as rebuilt text.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "base/outcome.h"
#include "base/work_farm.h"

namespace thaw::pipeline {

/// Items [first, first + count) of a farm, handed out together.
struct Chunk {
  long first = 0, count = 0;
};

/// n items cut for `ranks` ranks of `threads` threads: in order, covering [0, n), chunk sizes
/// non-increasing, multiples of `threads` but for the last, each about 1 / (4 ranks) of what is
/// left and at least `threads`.
std::vector<Chunk> guided_chunks(long n, int ranks, int threads);

/// What this process spent in one run() of the farm (a stage's phase: a 1D series' forms, then
/// its checks and surfaces), for bench/pipeline/mpi_scaling.sh's load-independent estimate (each
/// phase lasts, on an idle machine, about as long as its busiest rank's CPU seconds).
struct FarmCost {
  long items = 0;     ///< items of the whole run (all ranks)
  double cpu_s = 0;   ///< this process's CPU seconds during the run (all its threads)
  double wall_s = 0;  ///< wall seconds of the run on this process
  /// CPU seconds of this process's threads inside the items' work (no waiting, polling or
  /// hand-out): what the phase's items cost here, whatever the load.
  double work_cpu_s = 0;
  /// Items worked on by this process (with work_cpu_s: the CPU an item cost in this rank).
  long items_here = 0;
};

/// costs as one line: "farm 0 items 1 cpu_s 0.1234 wall_s 0.1300 work_cpu_s 0.1200 items_here 1;
/// farm 1 items ...".
std::string cost_note(const std::vector<FarmCost>& costs);

class RunRanks : public WorkFarm {
 public:
  virtual int rank() const { return 0; }
  virtual int size() const { return 1; }
  bool leader() const override { return rank() == 0; }
  int processes() const override { return size(); }
  std::string share(const std::string& text) override { return broadcast(text); }
  /// Returns when every rank has called it. Waiting ranks sleep rather than spin, so the cores
  /// stay with the rank that works (the leader simulating, say).
  virtual void barrier() {}
  /// The leader's `text` on every rank (what other ranks pass is ignored).
  virtual std::string broadcast(const std::string& text) { return text; }
  /// The first failure of every rank's `mine` (in rank order; ok if none failed), on every rank:
  /// how ranks that each ran the same step agree whether it failed.
  Outcome first_failure(const Outcome& mine) {
    return Outcome::from_text(first_nonempty(mine.to_text()));
  }
  /// WorkFarm::run over the ranks. Fine grain: guided chunks (guided_chunks), each on the threads
  /// of the rank that takes it, the next chunk asked for ahead. Coarse grain: one item at a time
  /// to whichever rank is free (dynamic: frames differ in cost). Every rank must call it with the
  /// same n and grain. With one rank: this process's threads (WorkFarm::run).
  std::vector<std::string> run(long n, int threads, const std::function<std::string(long)>& work,
                               const std::function<void()>& done,
                               Grain grain = Grain::fine) override;
  /// One entry per run(), in order.
  const std::vector<FarmCost>& costs() const { return m_costs; }

 protected:
  /// The transport under run(): calls work(item) exactly once for each of `items` over all ranks,
  /// one item at a time to whichever rank is free next, and returns on the leader the text each
  /// call returned, by position in `items` (other ranks: empty texts). On the leader,
  /// done(position) is called as each item finishes anywhere (never concurrently). If work throws
  /// on some rank, no further items are handed out and every rank then throws that first failure
  /// as it was (its outcome); items finished before stay finished. `ahead`: how many items a rank
  /// other than the leader asks for before it needs them (each hand-out is a round trip to the
  /// leader: asked ahead, it overlaps the rank's work). Of the last items (fewer than ranks) a
  /// rank gets none ahead: it gets one once its item in hand is done, so the last items go to
  /// whichever rank is free first. This process alone: a loop.
  virtual std::vector<std::string> hand_out(const std::vector<long>& items,
                                            const std::function<std::string(long)>& work,
                                            const std::function<void(long)>& done, int ahead);
  /// The first non-empty of every rank's `text` (in rank order), on every rank.
  virtual std::string first_nonempty(const std::string& text) { return text; }

 private:
  std::vector<std::string> run_on_ranks(long n, int threads,
                                        const std::function<std::string(long)>& work,
                                        const std::function<void()>& done, Grain grain);
  std::vector<FarmCost> m_costs;
};

/// One process: barrier and broadcast do nothing, the farm is this process's threads.
std::unique_ptr<RunRanks> single_process();

/// The ranks of the MPI job this process belongs to when it was started by mpirun / srun (built
/// with THAW_MPI and an MPI launcher's environment present), otherwise nullptr: a plain `thaw run`
/// never initialises MPI. MPI is initialised here and finalised when the object is destroyed.
std::unique_ptr<RunRanks> mpi_ranks_if_launched();

}  // namespace thaw::pipeline
