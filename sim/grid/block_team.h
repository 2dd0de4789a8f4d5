#pragma once
// The threads of one OpenMP parallel region working through fixed blocks of cells, meeting at a
// barrier that sleeps (futex, via std::atomic::wait) after a short spin.
//
// Why not OpenMP's own barriers: libgomp spins ~300000 pause instructions (about 10 ms) before
// it sleeps unless OMP_WAIT_POLICY=passive is set before the program starts, and on a shared
// machine a spinning thread takes the core that the thread it waits for needs: the grid solver
// ran 10x slower on 2 threads than on 1 (docs/benchmarks.md). One parallel region per time step
// with these barriers inside replaces ~10 fork/joins per conjugate-gradient iteration.
//
// Deterministic: the blocks are the same for any thread count (threads take them one at a time
// from a shared counter), so a per-block partial sum is computed by the same operations whoever
// computes it, and every thread adds the partials in block order. Knows nothing of the physics.
#include <algorithm>
#include <atomic>

namespace thaw::sim {

/// A reusable barrier for a fixed number of threads; the last to arrive wakes the others.
class SleepingBarrier {
 public:
  /// Must not be called while a thread waits.
  void reset(int threads) {
    m_threads = threads;
    m_arrived.store(0, std::memory_order_relaxed);
  }
  void wait() {
    if (m_threads <= 1) return;
    const unsigned generation = m_generation.load(std::memory_order_acquire);
    if (m_arrived.fetch_add(1, std::memory_order_acq_rel) + 1 == m_threads) {
      m_arrived.store(0, std::memory_order_relaxed);
      m_generation.fetch_add(1, std::memory_order_release);
      m_generation.notify_all();
      return;
    }
    // A short spin (a few microseconds) catches the balanced case without a system call.
    for (int i = 0; i < kSpin; ++i)
      if (m_generation.load(std::memory_order_acquire) != generation) return;
    while (m_generation.load(std::memory_order_acquire) == generation)
      m_generation.wait(generation, std::memory_order_acquire);
  }

 private:
  static constexpr int kSpin = 2000;
  std::atomic<int> m_arrived{0};
  std::atomic<unsigned> m_generation{0};
  int m_threads = 1;
};

/// What the threads of a team share: the barrier and the block dispensers of the phases.
struct TeamShared {
  SleepingBarrier barrier;
  /// Next block of the current phase (even and odd phases alternate, so one can be reset while
  /// the other is in use), on separate cache lines.
  struct alignas(64) Counter {
    std::atomic<long> next{0};
  };
  Counter counters[2];
};

/// One thread's view of the team. Blocks are handed out one at a time from a shared counter, so
/// a thread slowed down by the machine's other work (a compile sharing its core) holds up the
/// others by at most one block instead of its whole share: which thread computes a block does
/// not change what is computed, so results stay the same for any thread count and any timing.
class BlockTeam {
 public:
  BlockTeam(TeamShared& shared, int thread, long blocks)
      : m_shared(shared), m_thread(thread), m_blocks(blocks) {}
  /// f(block) for every block, shared out among the threads, then the barrier: afterwards every
  /// block is done. Every thread of the team must make the same sequence of calls.
  template <class F>
  void for_blocks(F&& f) {
    std::atomic<long>& next = m_shared.counters[m_phase & 1].next;
    for (long b = next.fetch_add(1, std::memory_order_relaxed); b < m_blocks;
         b = next.fetch_add(1, std::memory_order_relaxed))
      f(b);
    m_shared.barrier.wait();
    // Everybody is past this phase's counter: ready it for the phase after next. The barrier of
    // the next phase publishes the reset before anyone uses it again.
    if (leader()) next.store(0, std::memory_order_relaxed);
    ++m_phase;
  }
  /// Every thread waits here until all have arrived: what one thread wrote before is visible to
  /// all after (e.g. the leader's serial bookkeeping between phases).
  void sync() { m_shared.barrier.wait(); }
  /// f() on the leader only, then sync(): a serial part of the step, the others asleep meanwhile.
  template <class F>
  void serial(F&& f) {
    if (leader()) f();
    sync();
  }
  /// The one thread that updates shared bookkeeping (statistics).
  bool leader() const { return m_thread == 0; }

 private:
  TeamShared& m_shared;
  int m_thread;
  long m_blocks;
  long m_phase = 0;
};

}  // namespace thaw::sim
