#include "base/work_farm.h"

#include <omp.h>

#include <atomic>

namespace thaw {

std::vector<std::string> WorkFarm::run(long n, int threads,
                                       const std::function<std::string(long)>& work,
                                       const std::function<void()>& done, Grain grain) {
  std::vector<std::string> results(static_cast<std::size_t>(n > 0 ? n : 0));
  if (grain == Grain::coarse) {  // one at a time, each item using the threads itself
    for (long k = 0; k < n; ++k) {
      results[static_cast<std::size_t>(k)] = work(k);
      if (done) done();
    }
    return results;
  }
  // Nothing may leave the loop by an exception: each item's failure is kept as its outcome, the
  // items not yet begun are skipped, and the lowest failing item's outcome is thrown after it.
  std::vector<Outcome> failures(results.size());
  std::atomic<bool> failed{false};
#pragma omp parallel for schedule(dynamic, 1) \
    num_threads(threads > 0 ? threads : omp_get_max_threads())
  for (long k = 0; k < n; ++k) {
    if (failed.load(std::memory_order_relaxed)) continue;
    Outcome& outcome = failures[static_cast<std::size_t>(k)];
    outcome = Outcome::of([&] { results[static_cast<std::size_t>(k)] = work(k); });
    if (outcome.ok() && done) {
#pragma omp critical(thaw_work_farm_done)
      outcome = Outcome::of(done);
    }
    if (!outcome.ok()) failed = true;
  }
  if (failed)
    for (const Outcome& o : failures) o.rethrow();
  return results;
}

WorkFarm& this_process_farm() {
  static WorkFarm farm;
  return farm;
}

}  // namespace thaw
