#pragma once
// The stages of `thaw run`, one file each (stage_NAME.cpp); pipeline_stages() (pipeline.cpp)
// lists them in order. A new stage is a new file with its function here and in that list.
#include "src/pipeline/stage.h"

namespace thaw::pipeline {

/// 1. The simulation, sampled at exactly the frame times (the leader).
Stage simulate_stage();
/// 2. The inner and outer surface of every frame's step (every rank).
Stage mesh_stage();
/// 3. One frame per step, handed out over the ranks.
Stage render_stage();
/// 4. The film (and GIF) from every frame (the leader).
Stage film_stage();
/// 5. The plot, the ParaView series and the hand-off files (every rank).
Stage inspect_stage();

}  // namespace thaw::pipeline
