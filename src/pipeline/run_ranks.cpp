#include "src/pipeline/run_ranks.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <mutex>

namespace thaw::pipeline {
namespace {

// A chunk's texts as one: each prefixed by its length ("5:hello3:abc"), so any text survives.
std::string join(const std::vector<std::string>& texts) {
  std::string out;
  for (const std::string& t : texts) out += std::to_string(t.size()) + ":" + t;
  return out;
}

std::vector<std::string> split(const std::string& joined) {
  std::vector<std::string> texts;
  for (std::size_t at = 0; at < joined.size();) {
    const std::size_t colon = joined.find(':', at);
    const std::size_t length = std::stoul(joined.substr(at, colon - at));
    texts.push_back(joined.substr(colon + 1, length));
    at = colon + 1 + length;
  }
  return texts;
}

double cpu_s(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

std::string cost_note(const std::vector<FarmCost>& costs) {
  std::string note;
  for (std::size_t k = 0; k < costs.size(); ++k) {
    char buf[128];
    std::snprintf(buf, sizeof buf,
                  "%sfarm %zu items %ld cpu_s %.4f wall_s %.4f work_cpu_s %.4f items_here %ld",
                  k ? "; " : "", k, costs[k].items, costs[k].cpu_s, costs[k].wall_s,
                  costs[k].work_cpu_s, costs[k].items_here);
    note += buf;
  }
  return note;
}

std::vector<Chunk> guided_chunks(long n, int ranks, int threads) {
  // Guided self-scheduling (Polychronopoulos & Kuck 1987), with each chunk taking 1 / (4 R) of
  // what is left (their 1 / R, halved twice), in whole multiples of the threads: the first chunks
  // are large (few hand-outs) and the last ones a chunk of `threads` items (the ranks finish within
  // one item of each other). Not 1 / (2 R): a chunk, once taken, is its rank's to finish, and on a
  // shared machine a rank can lose its core for a while (measurements: docs/benchmarks.md).
  std::vector<Chunk> chunks;
  const long p = std::max(1, threads), r = std::max(1, ranks);
  for (long first = 0; first < n;) {
    const long left = n - first;
    const long share = (left + 4 * r - 1) / (4 * r);
    const long count = std::min(left, std::max(p, (share + p - 1) / p * p));
    chunks.push_back({first, count});
    first += count;
  }
  return chunks;
}

std::vector<std::string> RunRanks::hand_out(const std::vector<long>& items,
                                            const std::function<std::string(long)>& work,
                                            const std::function<void(long)>& done, int) {
  std::vector<std::string> results;
  for (long item : items) {
    results.push_back(work(item));
    if (done) done(static_cast<long>(results.size()) - 1);
  }
  return results;
}

std::vector<std::string> RunRanks::run(long n, int threads,
                                       const std::function<std::string(long)>& work,
                                       const std::function<void()>& done, Grain grain) {
  const double cpu0 = cpu_s(CLOCK_PROCESS_CPUTIME_ID);
  const auto wall0 = std::chrono::steady_clock::now();
  std::mutex mutex;
  double work_cpu = 0;
  long items_here = 0;
  const auto timed = [&](long k) {
    const double t0 = cpu_s(CLOCK_THREAD_CPUTIME_ID);
    std::string text = work(k);
    const double spent = cpu_s(CLOCK_THREAD_CPUTIME_ID) - t0;
    const std::lock_guard<std::mutex> lock(mutex);
    work_cpu += spent;
    ++items_here;
    return text;
  };
  std::vector<std::string> results = run_on_ranks(n, threads, timed, done, grain);
  m_costs.push_back(
      {n, cpu_s(CLOCK_PROCESS_CPUTIME_ID) - cpu0,
       std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count(), work_cpu,
       items_here});
  return results;
}

std::vector<std::string> RunRanks::run_on_ranks(long n, int threads,
                                                const std::function<std::string(long)>& work,
                                                const std::function<void()>& done, Grain grain) {
  if (size() == 1) return WorkFarm::run(n, threads, work, done, grain);
  if (grain == Grain::coarse) {
    std::vector<long> items(static_cast<std::size_t>(std::max(0L, n)));
    for (std::size_t k = 0; k < items.size(); ++k) items[k] = static_cast<long>(k);
    std::vector<std::string> results = hand_out(
        items, work,
        [&](long) {
          if (done) done();
        },
        0);
    results.resize(items.size());
    return results;
  }
  // Every hand-out is a round trip to the leader's dispatcher: guided chunks of
  // `threads`-multiples keep every thread busy with ~4 R log(n) hand-outs.
  const int per_rank = threads > 0 ? threads : omp_get_max_threads();
  const std::vector<Chunk> chunks = guided_chunks(n, size(), per_rank);
  std::vector<long> positions(chunks.size());
  for (std::size_t c = 0; c < chunks.size(); ++c) positions[c] = static_cast<long>(c);
  const std::vector<std::string> joined = hand_out(
      positions,
      [&](long c) {
        const Chunk& chunk = chunks[static_cast<std::size_t>(c)];
        return join(
            WorkFarm::run(chunk.count, threads, [&](long i) { return work(chunk.first + i); }, {}));
      },
      [&](long c) {  // progress in items: the finished chunk's worth
        if (done)
          for (long i = 0; i < chunks[static_cast<std::size_t>(c)].count; ++i) done();
      },
      1);  // the next chunk asked for while this one runs: no idle round trip between chunks
  std::vector<std::string> results(static_cast<std::size_t>(std::max(0L, n)));
  if (!leader()) return results;
  for (std::size_t c = 0; c < chunks.size(); ++c) {
    const std::vector<std::string> texts = split(joined[c]);
    for (std::size_t i = 0; i < texts.size(); ++i)
      results[static_cast<std::size_t>(chunks[c].first) + i] = texts[i];
  }
  return results;
}

std::unique_ptr<RunRanks> single_process() {
  return std::make_unique<RunRanks>();
}

}  // namespace thaw::pipeline
