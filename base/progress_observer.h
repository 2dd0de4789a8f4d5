#pragma once
// A hook for a program that embeds thaw (the Python module) and shows progress its own way: one
// process-wide observer that sees every update of every ProgressReporter (base/progress.h),
// quiet or not. Knows nothing about what is being computed.
#include <cstdint>

namespace thaw {

/// Sees every update of every ProgressReporter, quiet or not (for an embedding program such as
/// the Python module, which shows progress its own way): (context, title, done, total). Called
/// from whichever thread advances the work, OpenMP workers included: it must be quick and
/// thread-safe, and must not throw.
using ProgressObserver = void (*)(void* context, const char* title, std::int64_t done,
                                  std::int64_t total) noexcept;
/// Installs `observer` (nullptr: none) for the whole process, replacing the one before.
void set_progress_observer(ProgressObserver observer, void* context);

}  // namespace thaw
