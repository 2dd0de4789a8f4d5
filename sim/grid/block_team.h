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
// Deterministic: the blocks are the same for any thread count (each thread takes a contiguous
// range of them), so a per-block partial sum is computed by the same operations whoever computes
// it, and every thread adds the partials in block order. Knows nothing of the physics.
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

/// One thread's view: its contiguous share of `blocks` blocks, and the team's barrier.
class BlockTeam {
 public:
  BlockTeam(SleepingBarrier& barrier, int thread, int threads, long blocks)
      : m_barrier(barrier),
        m_thread(thread),
        m_first(blocks * thread / threads),
        m_last(blocks * (thread + 1) / threads) {}
  /// f(block) for this thread's blocks, then the barrier: afterwards every block is done.
  template <class F>
  void for_blocks(F&& f) {
    for (long b = m_first; b < m_last; ++b) f(b);
    m_barrier.wait();
  }
  /// The one thread that updates shared bookkeeping (statistics).
  bool leader() const { return m_thread == 0; }

 private:
  SleepingBarrier& m_barrier;
  int m_thread;
  long m_first, m_last;
};

}  // namespace thaw::sim
