#pragma once
// The mesh stage's farm (src/mesh/mesh_farm.h) over the ranks of a run (run_ranks.h): with one
// rank, that process's threads; with several, items handed out dynamically to the ranks, each
// rank taking a chunk of items at a time (guided_chunks) and meshing them on its threads. The
// ranks share the simulation folder, so the meshers exchange only short result texts through it.
#include "src/mesh/mesh_farm.h"
#include "src/pipeline/run_ranks.h"

namespace thaw::pipeline {

/// Items [first, first + count) of a farm, handed out together.
struct Chunk {
  long first = 0, count = 0;
};

/// n items cut for `ranks` ranks of `threads` threads: in order, covering [0, n), chunk sizes
/// non-increasing, multiples of `threads` but for the last, each about 1 / (4 ranks) of what is
/// left and at least `threads`.
std::vector<Chunk> guided_chunks(long n, int ranks, int threads);

/// What this process spent in one run() of a farm: the stage's phases (a 1D series: its forms,
/// then the checks and surfaces), for bench/pipeline/mpi_scaling.sh's load-independent estimate
/// (each phase lasts, on an idle machine, about as long as its busiest rank's CPU seconds).
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

class RanksMeshFarm final : public mesh::MeshFarm {
 public:
  explicit RanksMeshFarm(RunRanks& ranks) : m_ranks(ranks) {}
  bool leader() const override { return m_ranks.leader(); }
  std::string share(const std::string& text) override { return m_ranks.broadcast(text); }
  int processes() const override { return m_ranks.size(); }
  std::vector<std::string> run(long n, int threads, const std::function<std::string(long)>& work,
                               const std::function<void()>& done) override;
  /// One entry per run(), in order.
  const std::vector<FarmCost>& costs() const { return m_costs; }

 private:
  std::vector<std::string> run_on_ranks(long n, int threads,
                                        const std::function<std::string(long)>& work,
                                        const std::function<void()>& done);
  RunRanks& m_ranks;
  std::vector<FarmCost> m_costs;
};

/// costs as one line: "farm 0 items 1 cpu_s 0.1234 wall_s 0.1300 work_cpu_s 0.1200 items_here 1;
/// farm 1 items ...".
std::string cost_note(const std::vector<FarmCost>& costs);

}  // namespace thaw::pipeline
