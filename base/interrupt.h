#pragma once
// Clean ends on SIGINT and SIGTERM: the signal handler only sets a flag (and passes the signal on
// to a running child program such as ffmpeg); the work checks the flag at safe points (between
// steps, frames, surfaces and tiles) and throws Interrupted from sequential code, never inside an
// OpenMP loop. Unwinding removes every temporary output (atomic_file.h), so nothing is
// half-written, and main() prints one line and exits with 130. A second signal kills at once.
// Knows nothing about what is being computed.
#include <sys/types.h>

#include <stdexcept>

#include "base/progress.h"

namespace thaw {

/// Thrown at a safe point after SIGINT or SIGTERM; caught once by main().
class Interrupted : public std::runtime_error {
 public:
  Interrupted() : std::runtime_error("interrupted; run the same command again to resume") {}
};

/// The exit code of an interrupted command (128 + SIGINT, as shells report Ctrl-C).
inline constexpr int kInterruptedExitCode = 130;

/// Installs the SIGINT and SIGTERM handlers (once, at program start), then lets through the
/// signals hold_interrupt_signals() held back: one that arrived meanwhile reaches the handler.
void install_interrupt_handlers();

/// Blocks SIGINT and SIGTERM (they stay pending, not lost) until install_interrupt_handlers().
/// The block survives execve(2): the `thaw` launcher calls this before handing over to
/// thaw-full, whose ~115 libraries take a moment to load, so a signal in that moment still ends
/// the command cleanly (message, exit 130) instead of killing it by the default action.
void hold_interrupt_signals();

/// True once SIGINT or SIGTERM arrived (or request_interrupt() was called). Lock-free: may be
/// polled from OpenMP workers, which then skip their remaining work items.
bool interrupt_requested() noexcept;

/// Throws Interrupted if an interrupt was requested. Call only from sequential code.
void throw_if_interrupted();

/// What the handler does; tests call it directly. Async-signal-safe.
void request_interrupt() noexcept;
/// Forgets a request (tests only).
void clear_interrupt_request() noexcept;

/// The child program an interrupt is passed on to (0: none). Set by run_process() around its
/// wait, so SIGTERM sent to thaw alone also ends ffmpeg.
void set_interruptible_child(pid_t pid) noexcept;

/// `progress` preceded by throw_if_interrupted(): for callbacks that the algorithm calls from
/// sequential code only (between solver output times, between written files).
ProgressCallback interruptible(ProgressCallback progress);

}  // namespace thaw
