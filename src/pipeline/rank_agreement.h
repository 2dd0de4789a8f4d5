#pragma once
// How the ranks of a run agree that a step ended well or badly: the leader's step with its word
// to every rank (on_leader), or every rank's step with the first failure on all (on_every_rank),
// so that no rank waits for a rank that has given up. Knows nothing about what the step does.
#include <exception>
#include <string>

#include "base/error.h"
#include "src/pipeline/run_ranks.h"

namespace thaw::pipeline {

/// Runs `step` on the leader (rank 0) and tells every rank how it ended: a failure there (a user
/// error, or any other error when other ranks wait for the leader's word) is thrown on all ranks
/// as one UserError; with one rank, other errors propagate unchanged.
template <class Step>
void on_leader(RunRanks& ranks, Step&& step) {
  std::string error;
  if (ranks.leader()) try {
      step();
    } catch (const UserError& e) {
      error = e.what();
    } catch (const std::exception& e) {
      if (ranks.size() == 1) throw;
      error = std::string("internal error: ") + e.what();
    }
  error = ranks.broadcast(error);
  if (!error.empty()) throw UserError("", "", error);
}

/// Runs `step` on every rank (each doing its share) and makes them agree how it ended: the first
/// rank's failure is thrown on all ranks as one UserError. With one rank, errors propagate
/// unchanged.
template <class Step>
void on_every_rank(RunRanks& ranks, Step&& step) {
  if (ranks.size() == 1) return step();
  std::string error;
  try {
    step();
  } catch (const UserError& e) {
    error = e.what();
  } catch (const std::exception& e) {
    error = std::string("internal error: ") + e.what();
  }
  error = ranks.first_error(error);
  if (!error.empty()) throw UserError("", "", error);
}

}  // namespace thaw::pipeline
