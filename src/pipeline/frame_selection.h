#pragma once
// `thaw run --frames`: which film frames this process renders, so that Slurm job arrays and GNU
// parallel can share one run's frames between processes. Frames are numbered from 0 as their files
// are (frames/frame_000000.png). Forms: "7", "10-20" (inclusive), "3:40:2" (3, 5, ..., 39:
// start:last:step, last inclusive when reached, as Slurm's --array=3-40:2), "3:40" (step 1).
// Knows nothing about rendering; only counts.
#include <string>
#include <vector>

namespace thaw::pipeline {

struct FrameSelection {
  long first = 0;
  long last = 0;  ///< inclusive
  long step = 1;
  std::string text;  ///< as given, for messages

  /// The selected frame indices below `frame_count` in increasing order. Throws
  /// thaw::UserError("--frames", ...) if the selection starts at or beyond `frame_count`.
  std::vector<long> resolve(long frame_count) const;
};

/// Parses the forms above; throws thaw::UserError("--frames", problem) on anything else (empty,
/// negative, reversed, a zero step, trailing characters).
FrameSelection parse_frame_selection(const std::string& text);

}  // namespace thaw::pipeline
