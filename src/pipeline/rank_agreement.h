#pragma once
// How the ranks of a run agree that a step ended well or badly: the leader's step with its
// outcome sent to every rank (on_leader), or every rank's step with the first failure on all
// (on_every_rank), so that no rank waits for a rank that has given up. A failure keeps its kind
// (base/outcome.h): a user error its file and key (exit 2), an internal error stays one (exit 3).
// Knows nothing about what the step does.
#include <memory>

#include "base/outcome.h"
#include "src/pipeline/run_ranks.h"

namespace thaw::pipeline {

/// Runs `step` on the leader (rank 0) and throws how it ended on every rank. With one rank, its
/// exceptions propagate unchanged.
template <class Step>
void on_leader(RunRanks& ranks, Step&& step) {
  if (ranks.size() == 1) return step();
  Outcome outcome;
  if (ranks.leader()) outcome = Outcome::of(step);
  ranks.leaders_outcome(outcome).rethrow();
}

/// Runs `step` on every rank (each doing its share) and throws the first rank's failure on all
/// of them. With one rank, its exceptions propagate unchanged.
template <class Step>
void on_every_rank(RunRanks& ranks, Step&& step) {
  if (ranks.size() == 1) return step();
  ranks.first_failure(Outcome::of(step)).rethrow();
}

/// The end of a command that every rank ran (`thaw run` under mpirun), `mine` being how it ended
/// here. The leader throws its own outcome, which the command boundary prints once. Another rank
/// that failed says so itself only if the leader did not fail (the leader's line says it
/// otherwise), then finalises MPI (ranks.reset()) and exits with its outcome's exit code.
void end_on_ranks(std::unique_ptr<RunRanks>& ranks, const Outcome& mine);

}  // namespace thaw::pipeline
