#include "base/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <exception>

#include "base/progress_observer.h"

namespace thaw {
namespace {

// The observer and its context, read together under the lock (installs are rare; the lock is
// uncontended but for OpenMP workers advancing one reporter, which serialise on m_mutex anyway).
std::mutex g_observer_mutex;
ProgressObserver g_observer = nullptr;
void* g_observer_context = nullptr;

void notify_observer(const std::string& title, std::int64_t done, std::int64_t total) {
  std::lock_guard<std::mutex> lock(g_observer_mutex);
  if (g_observer) g_observer(g_observer_context, title.c_str(), done, total);
}

}  // namespace

void set_progress_observer(ProgressObserver observer, void* context) {
  std::lock_guard<std::mutex> lock(g_observer_mutex);
  g_observer = observer;
  g_observer_context = context;
}

ProgressReporter::ProgressReporter(std::string title, std::int64_t total, bool quiet)
    : m_title(std::move(title)),
      m_total(total < 0 ? 0 : total),
      m_quiet(quiet),
      m_tty(::isatty(STDERR_FILENO) != 0),
      m_start(std::chrono::steady_clock::now()),
      m_last_print(m_start),
      m_exceptions_at_start(std::uncaught_exceptions()) {}

ProgressReporter::~ProgressReporter() {
  // Unwinding from an error: no "done" line (the error's one line follows); a bar is cleared.
  if (std::uncaught_exceptions() > m_exceptions_at_start) {
    std::lock_guard<std::mutex> lock(m_mutex);
    if (!m_quiet && m_tty && !m_finished) std::fputs("\r\033[K", stderr);
    m_finished = true;
    return;
  }
  finish();
}

double ProgressReporter::elapsed_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
}

std::string ProgressReporter::format_duration(double s) {
  char buf[64];
  if (!std::isfinite(s) || s < 0) return "?";
  if (s < 60) {
    std::snprintf(buf, sizeof buf, "%.2f s", s);
  } else if (s < 3600) {
    const int total = static_cast<int>(std::lround(s));
    std::snprintf(buf, sizeof buf, "%d min %02d s", total / 60, total % 60);
  } else {
    const int total = static_cast<int>(std::lround(s / 60));
    std::snprintf(buf, sizeof buf, "%d h %02d min", total / 60, total % 60);
  }
  return buf;
}

void ProgressReporter::advance(std::int64_t items) {
  report(m_done += items, false);
}

void ProgressReporter::set_done(std::int64_t items_done) {
  m_done = items_done;
  report(items_done, false);
}

ProgressCallback ProgressReporter::callback() {
  // The algorithm knows its total best (a mesher counts shared meshes and copies).
  return [this](std::int64_t done, std::int64_t total) {
    if (total > 0) {
      std::lock_guard<std::mutex> lock(m_mutex);
      m_total = total;
    }
    set_done(done);
  };
}

void ProgressReporter::report(std::int64_t done, bool force) {
  std::lock_guard<std::mutex> lock(m_mutex);
  notify_observer(m_title, done, m_total);
  if (m_quiet || m_finished) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - m_start).count();
  const double frac = m_total > 0 ? std::min(1.0, double(done) / double(m_total)) : 1.0;
  const double eta = frac > 0 ? elapsed * (1.0 - frac) / frac : NAN;
  if (m_tty) {
    if (!force && now - m_last_print < std::chrono::milliseconds(100)) return;
    m_last_print = now;
    constexpr int width = 30;
    const int filled = static_cast<int>(frac * width);
    std::string bar(filled, '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r%s [%s] %lld/%lld  %s elapsed, ETA %s   ", m_title.c_str(), bar.c_str(),
                 static_cast<long long>(done), static_cast<long long>(m_total),
                 format_duration(elapsed).c_str(), format_duration(eta).c_str());
  } else {
    const int decile = static_cast<int>(frac * 10);
    if (!force && decile <= m_last_decile) return;
    m_last_decile = decile;
    std::fprintf(stderr, "%s: %lld/%lld (%d%%), %s elapsed, ETA %s\n", m_title.c_str(),
                 static_cast<long long>(done), static_cast<long long>(m_total),
                 static_cast<int>(frac * 100), format_duration(elapsed).c_str(),
                 format_duration(eta).c_str());
  }
  std::fflush(stderr);
}

void ProgressReporter::finish() {
  print_final("done", false);
}

void ProgressReporter::finish_early(const std::string& why) {
  print_final(why, true);
}

void ProgressReporter::print_final(const std::string& middle, bool parenthesised_time) {
  if (m_quiet) return;
  std::lock_guard<std::mutex> lock(m_mutex);
  if (m_finished) return;
  m_finished = true;
  const std::string elapsed = format_duration(elapsed_s());
  std::fprintf(stderr, "%s%s: %lld/%lld %s %s%s%s\n", m_tty ? "\r\033[K" : "", m_title.c_str(),
               static_cast<long long>(m_done.load()), static_cast<long long>(m_total),
               middle.c_str(), parenthesised_time ? "(" : "in ", elapsed.c_str(),
               parenthesised_time ? ")" : "");
  std::fflush(stderr);
}

}  // namespace thaw
