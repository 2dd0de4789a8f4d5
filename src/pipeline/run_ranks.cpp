#include "src/pipeline/run_ranks.h"

namespace thaw::pipeline {

std::vector<std::string> RunRanks::farm(const std::vector<long>& items,
                                        const std::function<std::string(long)>& work,
                                        const std::function<void(long, long)>& done, int) {
  std::vector<std::string> results;
  for (long item : items) {
    results.push_back(work(item));
    if (done) done(static_cast<long>(results.size()), static_cast<long>(results.size()) - 1);
  }
  return results;
}

std::unique_ptr<RunRanks> single_process() {
  return std::make_unique<RunRanks>();
}

}  // namespace thaw::pipeline
