#pragma once
// The files a scenario names, whose bytes are inputs of a run as much as its text: a [shape] OBJ
// (read by the simulation), a [render.environment] map and [[render.objects]] meshes (read by the
// render stage and the hand-off). Each stage adds the files it reads to its fingerprint, so a
// rerun after such a file changed redoes that stage and those after it (issue 27: a run used to
// keep stale results). A scenario names no other files: media and materials are built in, the
// floor's checker is procedural. Knows no stage; only which section names which file.
#include <filesystem>
#include <vector>

#include "src/pipeline/content_hash.h"
#include "src/pipeline/run_scenario.h"

namespace thaw::pipeline {

/// The files the simulation sections name ([shape] outer and cavity OBJs), as the solver opens
/// them.
std::vector<std::filesystem::path> simulation_input_files(const RunScenario& scenario);

/// The files [render] names (the environment map, object meshes), as the renderer opens them.
std::vector<std::filesystem::path> scene_input_files(const RunScenario& scenario);

/// Adds each file's bytes ("<missing>" for one that cannot be read) to `hash` (the paths are in
/// the sections' text already).
void add_input_files(ContentHash& hash, const std::vector<std::filesystem::path>& files);

}  // namespace thaw::pipeline
