#pragma once
// How a piece of work ended, as a value that crosses threads and MPI ranks without losing its
// kind: ok, a user error (file, where, problem: exit 2), an internal error (what: exit 3) or an
// interruption (exit 130). Caught where the work runs (Outcome::of), carried as a value or as
// text (to_text / from_text, for MPI), and thrown again as what it was (rethrow) where the
// failure is reported. Knows nothing about threads or ranks itself.
#include <exception>
#include <string>

namespace thaw {

/// The exit codes of the command boundary (src/cli/app.cpp).
inline constexpr int kUserErrorExitCode = 2;
inline constexpr int kInternalErrorExitCode = 3;

class Outcome {
 public:
  enum class Kind { ok, user, internal, interrupted };

  Outcome() = default;  ///< ok
  static Outcome user(std::string file, std::string where, std::string problem);
  static Outcome internal(std::string what);
  static Outcome interrupted();

  /// The exception being handled (call inside a catch block): UserError -> user, Interrupted ->
  /// interrupted, out of memory and any other exception -> internal.
  static Outcome of_current_exception() noexcept;
  /// Calls `work` and returns how it ended; nothing escapes.
  template <class Work>
  static Outcome of(Work&& work) noexcept {
    try {
      work();
      return {};
    } catch (...) {
      return of_current_exception();
    }
  }

  Kind kind() const noexcept { return m_kind; }
  bool ok() const noexcept { return m_kind == Kind::ok; }
  /// user: the file concerned ("" if none) and where in it ("" if nowhere)
  const std::string& file() const noexcept { return m_file; }
  const std::string& where() const noexcept { return m_where; }
  /// user: what is wrong; internal: what failed; interrupted: what to do
  const std::string& problem() const noexcept { return m_problem; }
  /// The line the command boundary prints for it (UserError::what(), say).
  std::string message() const;
  /// kUserErrorExitCode, kInternalErrorExitCode, kInterruptedExitCode, or 0 if ok.
  int exit_code() const noexcept;

  /// Throws what it stands for: thaw::UserError, thaw::Interrupted, or (internal) a
  /// std::runtime_error with its text; returns if ok.
  void rethrow() const;

  /// Its text form: "" if ok, otherwise one kind letter and length-prefixed fields, so that any
  /// text (newlines, colons) survives. from_text(to_text(o)) equals o; from_text of text that is
  /// no outcome is an internal error saying so.
  std::string to_text() const;
  static Outcome from_text(const std::string& text);

  friend bool operator==(const Outcome&, const Outcome&) = default;

 private:
  Kind m_kind = Kind::ok;
  std::string m_file, m_where, m_problem;
};

}  // namespace thaw
