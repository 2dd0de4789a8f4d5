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
/// non-increasing, multiples of `threads` but for the last, each about 1 / (2 ranks) of what is
/// left and at least `threads`.
std::vector<Chunk> guided_chunks(long n, int ranks, int threads);

class RanksMeshFarm final : public mesh::MeshFarm {
 public:
  explicit RanksMeshFarm(RunRanks& ranks) : m_ranks(ranks) {}
  bool leader() const override { return m_ranks.leader(); }
  std::string share(const std::string& text) override { return m_ranks.broadcast(text); }
  std::vector<std::string> run(long n, int threads, const std::function<std::string(long)>& work,
                               const std::function<void()>& done) override;

 private:
  RunRanks& m_ranks;
};

}  // namespace thaw::pipeline
