#include "src/mesh/mesh_farm.h"

#include "base/outcome.h"

namespace thaw::mesh {

std::filesystem::path stage_on_leader(WorkFarm& farm, std::optional<StagingDirectory>& staging,
                                      const std::filesystem::path& final_dir) {
  Outcome staged;
  if (farm.leader()) staged = Outcome::of([&] { staging.emplace(final_dir); });
  farm.leaders_outcome(staged).rethrow();
  return farm.share(staging ? staging->path().string() : "");
}

}  // namespace thaw::mesh
