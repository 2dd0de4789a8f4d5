#pragma once
// `thaw run --size WxH --spp N --fps F`: image and film settings given on the command line for a
// quick preview or a final render, replacing the scenario's [render.image] / [film] values. Size
// and samples count in the render stage's fingerprint only, the frame rate in the film's only,
// so changing them neither re-simulates nor re-meshes. Validated by the same rules as the
// scenario's keys (render/scene/scene_rules.h, fps_problem in run_scenario.h).
#include <optional>
#include <string>

#include "src/pipeline/run_scenario.h"

namespace thaw::pipeline {

struct RenderOverrides {
  std::optional<int> width, height;      ///< [pixels]
  std::optional<int> samples_per_pixel;  ///< [render.image] samples_per_pixel
  std::optional<double> fps;             ///< melt.mp4's frame rate (FilmSettings::playback_fps)
};

/// Parses "640x480" (also "640X480"); throws thaw::UserError(--size, problem) for anything else,
/// a side outside 1..kMaxImageSide or more than kMaxImagePixels pixels.
RenderOverrides parse_size_override(const std::string& text);

/// Checks `spp` by the samples_per_pixel rule (render/scene/scene_rules.h); throws
/// thaw::UserError(--spp, problem).
int checked_spp_override(long long spp);

/// Checks a --fps value by fps_problem; throws thaw::UserError(--fps, problem).
double checked_fps_override(double fps);

/// Replaces the scenario's image and film settings and adds the overrides to the render and film
/// fingerprints.
void apply_render_overrides(RunScenario& scenario, const RenderOverrides& overrides);

}  // namespace thaw::pipeline
