#include "src/pipeline/frame_selection.h"

#include <algorithm>
#include <charconv>
#include <string_view>

#include "base/error.h"

namespace thaw::pipeline {
namespace {

[[noreturn]] void fail(const std::string& text, const std::string& part,
                       const std::string& problem) {
  throw UserError(
      "", "--frames",
      problem + (part == text ? "" : " in \"" + part + "\"") + " (got \"" + text + "\")");
}

constexpr const char* kForms =
    "expected frames N, ranges FIRST-LAST or FIRST:LAST:STEP, separated by commas, e.g. 17,36 or "
    "10-20 or 3:40:2";

long frame_number(std::string_view s, const std::string& part, const std::string& text) {
  if (!s.empty() && s.front() == '-') fail(text, part, "frame numbers start at 0");
  long v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size()) fail(text, part, kForms);
  return v;
}

FrameSelection::Part parse_part(std::string_view s, const std::string& text) {
  FrameSelection::Part f;
  f.text = std::string(s);
  const std::string& part = f.text;
  if (s.empty()) fail(text, part, "an empty part: " + std::string(kForms));
  // A leading '-' is a negative number, not a range.
  const auto dash = s.find('-', 1), colon = s.find(':');
  if (dash != std::string_view::npos && colon == std::string_view::npos) {
    f.first = frame_number(s.substr(0, dash), part, text);
    f.last = frame_number(s.substr(dash + 1), part, text);
  } else if (colon != std::string_view::npos && dash == std::string_view::npos) {
    const auto second = s.find(':', colon + 1);
    f.first = frame_number(s.substr(0, colon), part, text);
    if (second == std::string_view::npos) {
      f.last = frame_number(s.substr(colon + 1), part, text);
    } else {
      f.last = frame_number(s.substr(colon + 1, second - colon - 1), part, text);
      f.step = frame_number(s.substr(second + 1), part, text);
      if (f.step == 0) fail(text, part, "the step must be at least 1");
    }
  } else if (dash != std::string_view::npos) {
    fail(text, part, "a part is FIRST-LAST or FIRST:LAST:STEP, not both");
  } else {
    f.first = f.last = frame_number(s, part, text);
  }
  if (f.last < f.first) fail(text, part, "the last frame comes before the first");
  return f;
}

}  // namespace

FrameSelection parse_frame_selection(const std::string& text) {
  FrameSelection f;
  f.text = text;
  const std::string_view s(text);
  for (std::size_t begin = 0;;) {
    const std::size_t comma = s.find(',', begin);
    f.parts.push_back(parse_part(s.substr(begin, comma - begin), text));
    if (comma == std::string_view::npos) break;
    begin = comma + 1;
  }
  return f;
}

std::vector<long> FrameSelection::resolve(long frame_count) const {
  std::vector<long> frames;
  for (const Part& p : parts) {
    if (p.first >= frame_count)
      throw UserError("", "--frames",
                      "the film has frames 0-" + std::to_string(frame_count - 1) + " (got \"" +
                          (p.text == text ? text : p.text + "\" in \"" + text) + "\")");
    for (long k = p.first; k <= p.last && k < frame_count; k += p.step) {
      frames.push_back(k);
      if (p.last - k < p.step) break;  // no overflow past LONG_MAX
    }
  }
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  return frames;
}

}  // namespace thaw::pipeline
