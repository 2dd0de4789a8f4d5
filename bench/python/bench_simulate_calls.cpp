// The C++ side of bench_python.py: `bench_simulate_calls SCENARIO.toml N` parses the scenario
// once, then calls sim::simulate N times as thaw.simulate does (with a quiet progress bar and
// the interrupt check), and prints one line per call: wall seconds, CPU seconds of the process.
// Knows nothing of Python.
#include <time.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "base/interrupt.h"
#include "base/progress.h"
#include "sim/format/scenario_file.h"
#include "sim/simulate.h"

namespace {

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: bench_simulate_calls SCENARIO.toml N\n");
    return 2;
  }
  const thaw::sim::Scenario scenario = thaw::sim::read_scenario_file(argv[1]);
  const long n = std::atol(argv[2]);
  for (long k = 0; k < n; ++k) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu = cpu_seconds();
    thaw::ProgressReporter bar(
        "simulate", static_cast<std::int64_t>(thaw::sim::output_times(scenario).size()), true);
    const auto r = thaw::sim::simulate(scenario, thaw::interruptible(bar.callback()));
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%.9f %.9f %zu\n", wall, cpu_seconds() - cpu, r.snapshots.size());
  }
  return 0;
}
