#include "src/mesh/mesh_farm.h"

#include <omp.h>

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

MeshFarm& this_process_farm() {
  static MeshFarm farm;
  return farm;
}

}  // namespace thaw::mesh
