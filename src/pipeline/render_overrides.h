#pragma once
// `thaw run --size WxH --spp N`: image settings given on the command line for a quick preview or
// a final render, replacing the scenario's [render.image] values. They count in the render
// stage's fingerprint only, so changing them re-renders without re-simulating or re-meshing.
// Validated against the scene parser's limits (render/scene/scene_parser.h).
#include <optional>
#include <string>

#include "src/pipeline/run_scenario.h"

namespace thaw::pipeline {

struct RenderOverrides {
  std::optional<int> width, height;      ///< [pixels]
  std::optional<int> samples_per_pixel;  ///< [render.image] samples_per_pixel
};

/// Parses "640x480" (also "640X480"); throws thaw::UserError(--size, problem) for anything else,
/// a side outside 1..kMaxImageSide or more than kMaxImagePixels pixels.
RenderOverrides parse_size_override(const std::string& text);

/// Checks `spp` against the scene parser's range; throws thaw::UserError(--spp, problem).
int checked_spp_override(long long spp);

/// Replaces the scenario's image settings and adds the overrides to its render fingerprint.
void apply_render_overrides(RunScenario& scenario, const RenderOverrides& overrides);

}  // namespace thaw::pipeline
