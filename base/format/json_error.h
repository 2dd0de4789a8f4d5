#pragma once
// The user-facing text of a nlohmann::json exception: its description without the library's
// "[json.exception.parse_error.101] " tag, for UserErrors about malformed JSON inputs
// (summary.json, mesh manifests, run manifests). Knows nothing about what the JSON holds.
#include <nlohmann/json.hpp>
#include <string>

namespace thaw {

inline std::string json_problem(const nlohmann::json::exception& e) {
  const std::string what = e.what();
  if (what.rfind("[json.exception.", 0) == 0) {
    const std::size_t end = what.find("] ");
    if (end != std::string::npos) return what.substr(end + 2);
  }
  return what;
}

}  // namespace thaw
