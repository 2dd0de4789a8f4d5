#pragma once
// Errors that are the user's to fix: a file, a key (or line) in it, and what is wrong.
// Thrown at boundaries (parsing, I/O), caught once at the command boundary, printed as one line,
// exit code 2. Internal invariants use THAW_CHECK (src/common/check.h) instead; never mix them.
#include <stdexcept>
#include <string>
#include <utility>

namespace thaw {

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
    return line + problem;
  }
  std::string m_file, m_where, m_problem;
};

}  // namespace thaw
