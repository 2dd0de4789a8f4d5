#pragma once
// The processes sharing one `thaw run`: a single process, or the ranks of an MPI job
// (run_ranks_mpi.h, built with THAW_MPI). The pipeline asks them to wait for each other, to share
// the leader's word and to farm out frames; it never sees MPI. Rank 0, the leader, simulates,
// keeps run_manifest.json and makes the film; frames go to whichever rank asks next.
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace thaw::pipeline {

class RunRanks {
 public:
  virtual ~RunRanks() = default;
  virtual int rank() const { return 0; }
  virtual int size() const { return 1; }
  bool leader() const { return rank() == 0; }
  /// Returns when every rank has called it. Waiting ranks sleep rather than spin, so the cores
  /// stay with the rank that works (the leader simulating, say).
  virtual void barrier() {}
  /// The leader's `text` on every rank (what other ranks pass is ignored).
  virtual std::string broadcast(const std::string& text) { return text; }
  /// Calls work(item) exactly once for each of `items` over all ranks, one item at a time to
  /// whichever rank is free next (dynamic: frames differ in cost), and returns on the leader the
  /// text each call returned, by position in `items` (other ranks: empty texts). On the leader,
  /// done(n, position) is called as the n-th item finishes anywhere, `position` being that item's
  /// index in `items` (never concurrently). If work throws on some rank, no further
  /// items are handed out and every rank then throws thaw::UserError with that rank's message
  /// (the first failure); items finished before stay finished. Every rank must call farm with
  /// equal items. `ahead`: how many items a rank other than the leader asks for before it needs
  /// them (each hand-out is a round trip to the leader: asked ahead, it overlaps the rank's work).
  /// Of the last items (fewer than ranks) a rank gets none ahead: it gets one once its item in
  /// hand is done, so the last items go to whichever rank is free first. For short items: a rank
  /// may still hold up to `ahead` items a little before the end.
  virtual std::vector<std::string> farm(const std::vector<long>& items,
                                        const std::function<std::string(long)>& work,
                                        const std::function<void(long, long)>& done, int ahead = 0);
  /// The first non-empty of every rank's `error` (in rank order), on every rank: how ranks that
  /// each ran the same step agree whether it failed.
  virtual std::string first_error(const std::string& error) { return error; }
};

/// One process: barrier and broadcast do nothing, farm is a loop.
std::unique_ptr<RunRanks> single_process();

/// The ranks of the MPI job this process belongs to when it was started by mpirun / srun (built
/// with THAW_MPI and an MPI launcher's environment present), otherwise nullptr: a plain `thaw run`
/// never initialises MPI. MPI is initialised here and finalised when the object is destroyed.
std::unique_ptr<RunRanks> mpi_ranks_if_launched();

}  // namespace thaw::pipeline
