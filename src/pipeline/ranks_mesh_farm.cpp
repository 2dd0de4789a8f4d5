#include "src/pipeline/ranks_mesh_farm.h"

#include <omp.h>

#include <algorithm>

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

}  // namespace

std::vector<std::string> RanksMeshFarm::run(long n, int threads,
                                            const std::function<std::string(long)>& work,
                                            const std::function<void()>& done) {
  if (m_ranks.size() == 1) return MeshFarm::run(n, threads, work, done);
  // Chunks of `threads` items keep every thread of every rank busy; the last chunks are small
  // enough for the dynamic hand-out to even out the ranks.
  const long chunk = std::max(1, threads > 0 ? threads : omp_get_max_threads());
  long reported = 0;
  std::vector<long> chunks;
  for (long first = 0; first < n; first += chunk) chunks.push_back(first);
  const std::vector<std::string> joined = m_ranks.farm(
      chunks,
      [&](long first) {
        const long count = std::min(chunk, n - first);
        return join(MeshFarm::run(count, threads, [&](long i) { return work(first + i); }, {}));
      },
      [&](long chunks_done) {  // progress in items: a chunk's worth each (the last: the rest)
        const long target =
            chunks_done == static_cast<long>(chunks.size()) ? n : std::min(n, chunks_done * chunk);
        for (; reported < target; ++reported)
          if (done) done();
      });
  std::vector<std::string> results(static_cast<std::size_t>(std::max(0L, n)));
  if (!m_ranks.leader()) return results;
  for (std::size_t c = 0; c < chunks.size(); ++c) {
    const std::vector<std::string> texts = split(joined[c]);
    for (std::size_t i = 0; i < texts.size(); ++i)
      results[static_cast<std::size_t>(chunks[c]) + i] = texts[i];
  }
  return results;
}

}  // namespace thaw::pipeline
