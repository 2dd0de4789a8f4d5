#include "src/pipeline/rank_agreement.h"

#include <cstdio>
#include <cstdlib>

#include "base/error.h"

namespace thaw::pipeline {

void end_on_ranks(std::unique_ptr<RunRanks>& ranks, const Outcome& mine) {
  const Outcome leaders = ranks->leaders_outcome(mine);
  if (ranks->leader()) return mine.rethrow();
  if (mine.ok()) return;
  if (leaders.ok())
    std::fprintf(stderr, "thaw: %s (rank %d): %s\n",
                 mine.kind() == Outcome::Kind::internal ? "internal error" : "error", ranks->rank(),
                 escape_control_characters(mine.message()).c_str());
  ranks.reset();  // MPI_Finalize, then leave without a second copy of the leader's line
  std::exit(mine.exit_code());
}

}  // namespace thaw::pipeline
