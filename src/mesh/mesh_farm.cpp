#include "src/mesh/mesh_farm.h"

#include <omp.h>

#include "base/error.h"

namespace thaw::mesh {

std::vector<std::string> MeshFarm::run(long n, int threads,
                                       const std::function<std::string(long)>& work,
                                       const std::function<void()>& done) {
  std::vector<std::string> results(static_cast<std::size_t>(n > 0 ? n : 0));
  const int jobs = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(jobs)
  for (long k = 0; k < n; ++k) {
    results[static_cast<std::size_t>(k)] = work(k);
    if (done) {
#pragma omp critical(thaw_mesh_farm_done)
      done();
    }
  }
  return results;
}

std::filesystem::path stage_on_leader(MeshFarm& farm, std::optional<StagingDirectory>& staging,
                                      const std::filesystem::path& final_dir) {
  std::optional<UserError> failed;
  if (farm.leader()) try {
      staging.emplace(final_dir);
    } catch (const UserError& e) {
      failed = e;
    }
  // "+path" or "-message": one word from the leader either way.
  std::string said(1, failed ? '-' : '+');
  said += failed ? std::string(failed->what()) : staging ? staging->path().string() : "";
  const std::string word = farm.share(said);
  if (failed) throw *failed;
  if (word.empty() || word[0] == '-')
    throw UserError("", "", word.empty() ? final_dir.string() + ": not staged" : word.substr(1));
  return word.substr(1);
}

MeshFarm& this_process_farm() {
  static MeshFarm farm;
  return farm;
}

}  // namespace thaw::mesh
