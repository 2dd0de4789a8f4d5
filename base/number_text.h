#pragma once
// Numbers in messages and written files: the shortest text that reads back as the same double
// ("0.04", not "0.040000000000000001"), by std::to_chars' shortest round trip. Knows nothing of
// the file formats that use it.
#include <charconv>
#include <string>

namespace thaw {

inline std::string shortest_text(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace thaw
