#pragma once
// `thaw run --frames`: which film frames this process renders, so that Slurm job arrays and GNU
// parallel can share one run's frames between processes, and a user can pick frames to look at.
// Frames are numbered from 0 as their files are (frames/frame_000000.png). A selection is a
// comma-separated list of parts, each "7", "10-20" (inclusive), "3:40:2" (3, 5, ..., 39:
// start:last:step, last inclusive when reached, as Slurm's --array=3-40:2) or "3:40" (step 1):
// "17,36", "0-4,10:40:10". Knows nothing about rendering; only counts.
#include <string>
#include <vector>

namespace thaw::pipeline {

struct FrameSelection {
  /// One part of the list: first..last (inclusive) by step.
  struct Part {
    long first = 0;
    long last = 0;  ///< inclusive
    long step = 1;
    std::string text;  ///< this part as given, for messages
  };
  std::vector<Part> parts;
  std::string text;  ///< as given, for messages

  /// The selected frame indices below `frame_count`, in increasing order, each once. Throws
  /// thaw::UserError("--frames", ...) if a part starts at or beyond `frame_count` (a range that
  /// only reaches past the end is cut there: a job array's last chunk).
  std::vector<long> resolve(long frame_count) const;
};

/// Parses the forms above; throws thaw::UserError("--frames", problem) on anything else (empty,
/// an empty part, negative, reversed, a zero step, trailing characters), naming the bad part.
FrameSelection parse_frame_selection(const std::string& text);

}  // namespace thaw::pipeline
