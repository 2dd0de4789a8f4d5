#include "src/pipeline/frame_selection.h"

#include <charconv>
#include <string_view>

#include "base/error.h"

namespace thaw::pipeline {
namespace {

[[noreturn]] void fail(const std::string& text, const std::string& problem) {
  throw UserError("", "--frames", problem + " (got \"" + text + "\")");
}

long frame_number(std::string_view s, const std::string& text) {
  long v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size())
    fail(text, "expected a frame N, a range FIRST-LAST or FIRST:LAST:STEP, e.g. 10-20 or 3:40:2");
  if (v < 0) fail(text, "frame numbers start at 0");
  return v;
}

}  // namespace

FrameSelection parse_frame_selection(const std::string& text) {
  FrameSelection f;
  f.text = text;
  const std::string_view s(text);
  const auto dash = s.find('-'), colon = s.find(':');
  if (dash != std::string_view::npos && colon == std::string_view::npos) {
    f.first = frame_number(s.substr(0, dash), text);
    f.last = frame_number(s.substr(dash + 1), text);
  } else if (colon != std::string_view::npos && dash == std::string_view::npos) {
    const auto second = s.find(':', colon + 1);
    f.first = frame_number(s.substr(0, colon), text);
    if (second == std::string_view::npos) {
      f.last = frame_number(s.substr(colon + 1), text);
    } else {
      f.last = frame_number(s.substr(colon + 1, second - colon - 1), text);
      f.step = frame_number(s.substr(second + 1), text);
      if (f.step == 0) fail(text, "the step must be at least 1");
    }
  } else {
    f.first = f.last = frame_number(s, text);
  }
  if (f.last < f.first) fail(text, "the last frame comes before the first");
  return f;
}

std::vector<long> FrameSelection::resolve(long frame_count) const {
  if (first >= frame_count)
    throw UserError(
        "", "--frames",
        "the film has frames 0-" + std::to_string(frame_count - 1) + " (got \"" + text + "\")");
  std::vector<long> frames;
  for (long k = first; k <= last && k < frame_count; k += step) frames.push_back(k);
  return frames;
}

}  // namespace thaw::pipeline
