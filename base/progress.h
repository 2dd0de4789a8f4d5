#pragma once
// Progress display with an ETA, kept out of the algorithms (they take a callback). On a terminal
// it redraws one line on stderr; otherwise it prints a plain line every 10 % of the work.
// Thread-safe: advance() may be called from OpenMP workers.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>

namespace thaw {

/// What algorithms see: called with (items done, items total).
using ProgressCallback = std::function<void(std::int64_t, std::int64_t)>;

class ProgressReporter {
 public:
  /// title: shown before the bar; total: number of work items (>= 0); quiet: print nothing.
  ProgressReporter(std::string title, std::int64_t total, bool quiet = false);
  ~ProgressReporter();

  void advance(std::int64_t items = 1);
  void set_done(std::int64_t items_done);
  /// Prints the final line, "title: 41/41 done in 2.10 s"; called by the destructor if not
  /// called before, unless the destructor runs because an error is unwinding the work (then
  /// nothing is printed: the error is the one line).
  void finish();
  /// The final line of work that legitimately stopped short of its total, saying why:
  /// "title: 51/80 steps: the ice is gone (2.10 s)" for finish_early("steps: the ice is gone").
  void finish_early(const std::string& why);
  double elapsed_s() const;
  /// For algorithms: set_done(done), and a positive total replaces the one given here.
  ProgressCallback callback();

  /// Human-readable duration: "0.42 s", "3 min 05 s", "1 h 02 min".
  static std::string format_duration(double seconds);

 private:
  void report(std::int64_t done, bool force);
  void print_final(const std::string& middle, bool parenthesised_time);
  std::string m_title;
  std::int64_t m_total;
  bool m_quiet, m_tty, m_finished = false;
  std::atomic<std::int64_t> m_done{0};
  std::chrono::steady_clock::time_point m_start, m_last_print;
  int m_exceptions_at_start;  ///< std::uncaught_exceptions() when made: the destructor unwinds?
  int m_last_decile = -1;
  std::mutex m_mutex;
};

}  // namespace thaw
