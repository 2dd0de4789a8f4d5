#pragma once
// How the meshers share one output folder over the processes of a work farm (base/work_farm.h):
// the leader stages the folder and every process learns where. The meshers hand their items
// (distinct surfaces, grid steps) to the farm; by default this process's threads, under
// `thaw run` with MPI the run's ranks (src/pipeline). Nothing here knows about MPI.
#include <filesystem>
#include <optional>

#include "base/atomic_file.h"
#include "base/work_farm.h"

namespace thaw::mesh {

/// The leader stages `final_dir` into `staging`; every process gets the staged folder's path. A
/// failure to stage is thrown on every process as it was (base/outcome.h), so that no process
/// waits for a leader that has given up.
std::filesystem::path stage_on_leader(WorkFarm& farm, std::optional<StagingDirectory>& staging,
                                      const std::filesystem::path& final_dir);

}  // namespace thaw::mesh
