#include "base/interrupt.h"

#include <pthread.h>
#include <signal.h>

#include <atomic>
#include <utility>

namespace thaw {
namespace {

// Lock-free atomics are async-signal-safe (a plain volatile sig_atomic_t would not be visible
// to the OpenMP workers without a race).
std::atomic<bool> g_requested{false};
std::atomic<pid_t> g_child{0};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<pid_t>::is_always_lock_free);

extern "C" void on_interrupt_signal(int signal_number) {
  g_requested.store(true);
  // kill(2) is async-signal-safe; the child ends and run_process() sees the request.
  const pid_t child = g_child.load();
  if (child > 0) ::kill(child, signal_number == SIGINT ? SIGINT : SIGTERM);
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_interrupt_signal;
  sigemptyset(&action.sa_mask);
  // SA_RESETHAND: a second Ctrl-C takes the default action and ends the process at once (its
  // temporaries are removed by the next run, atomic_file.h remove_stale_temporaries).
  action.sa_flags = SA_RESETHAND | SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  sigset_t held;
  sigemptyset(&held);
  sigaddset(&held, SIGINT);
  sigaddset(&held, SIGTERM);
  pthread_sigmask(SIG_UNBLOCK, &held, nullptr);
}

void hold_interrupt_signals() {
  sigset_t held;
  sigemptyset(&held);
  sigaddset(&held, SIGINT);
  sigaddset(&held, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &held, nullptr);
}

bool interrupt_requested() noexcept {
  return g_requested.load(std::memory_order_relaxed);
}

void throw_if_interrupted() {
  if (interrupt_requested()) throw Interrupted();
}

void request_interrupt() noexcept {
  on_interrupt_signal(SIGINT);
}

void clear_interrupt_request() noexcept {
  g_requested.store(false);
}

void set_interruptible_child(pid_t pid) noexcept {
  g_child.store(pid);
}

ProgressCallback interruptible(ProgressCallback progress) {
  return [progress = std::move(progress)](std::int64_t done, std::int64_t total) {
    throw_if_interrupted();
    if (progress) progress(done, total);
  };
}

}  // namespace thaw
