#pragma once
// Errors that are the user's to fix: a file, a key (or line) in it, and what is wrong.
// Thrown at boundaries (parsing, I/O), caught once at the command boundary, printed as one line,
// exit code 2; control characters in any part are escaped, so the line is always one line.
// Internal invariants use THAW_CHECK (base/check.h) instead; never mix them.
#include <stdexcept>
#include <string>
#include <utility>

namespace thaw {

/// `text` with every control character (newline, tab, escape, DEL ...) written as a C escape
/// (backslash-n, backslash-t, backslash-x1b), so a message quoting user input stays one line.
inline std::string escape_control_characters(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  static const char* hex = "0123456789abcdef";
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u != 0x7f) {
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else {
      out += "\\x";
      out += hex[u >> 4];
      out += hex[u & 15];
    }
  }
  return out;
}

class UserError : public std::runtime_error {
 public:
  /// file: the input or output concerned ("" if none); where: key, "line N" or "" ;
  /// problem: what is wrong, including the offending value where there is one.
  UserError(std::string file, std::string where, std::string problem)
      : std::runtime_error(format(file, where, problem)),
        m_file(std::move(file)),
        m_where(std::move(where)),
        m_problem(std::move(problem)) {}

  const std::string& file() const noexcept { return m_file; }
  const std::string& where() const noexcept { return m_where; }
  const std::string& problem() const noexcept { return m_problem; }

 private:
  static std::string format(const std::string& file, const std::string& where,
                            const std::string& problem) {
    std::string line;
    if (!file.empty()) line += file + ": ";
    if (!where.empty()) line += where + ": ";
    return escape_control_characters(line + problem);
  }
  std::string m_file, m_where, m_problem;
};

}  // namespace thaw
