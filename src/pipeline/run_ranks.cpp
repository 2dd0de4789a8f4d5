#include "src/pipeline/run_ranks.h"

namespace thaw::pipeline {

void RunRanks::farm(const std::vector<long>& items, const std::function<void(long)>& work,
                    const std::function<void(long)>& done) {
  long n = 0;
  for (long item : items) {
    work(item);
    if (done) done(++n);
  }
}

std::unique_ptr<RunRanks> single_process() {
  return std::make_unique<RunRanks>();
}

}  // namespace thaw::pipeline
