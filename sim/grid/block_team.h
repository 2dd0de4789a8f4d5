#pragma once
// The threads of one OpenMP parallel region working through fixed blocks of cells: one thread
// (the leader) runs the solver's control flow and posts each phase (a function of a block
// index); the others (helpers) take the phase's blocks one at a time from a shared counter, as
// the leader does, and sleep (futex, via std::atomic::wait) after a short spin between phases.
//
// Why this shape: on a machine shared with other work a thread is often descheduled for a
// time slice (milliseconds). With a barrier every thread must arrive, so a descheduled thread
// holds the others up at every phase. Here the leader never waits for a helper to arrive: a
// phase ends when its last block is done, so a helper that sleeps or is descheduled between
// blocks costs nothing (the leader does the blocks itself); only a helper descheduled in the
// middle of a block makes the leader wait for that block. The serial parts between phases are
// plain code on the leader. (OpenMP's own barriers also spin ~300000 pauses before sleeping
// unless OMP_WAIT_POLICY=passive: the solver once ran 10x slower on 2 threads than on 1.)
//
// Deterministic: the blocks are the same for any thread count, so a per-block partial sum is
// computed by the same operations whoever computes it, and the leader adds the partials in
// block order. Knows nothing of the physics.
#include <atomic>
#include <cstdint>
#include <type_traits>

namespace thaw::sim {

/// What the threads of a team share: the posted phase and its block counter.
struct TeamShared {
  /// generation << 32 | next unclaimed block of the current phase. A helper claims a block only
  /// by a compare-exchange that checks the generation, so it never runs a block of a phase that
  /// has ended. Starts with no phase posted (generation 0, every block taken).
  alignas(64) std::atomic<std::uint64_t> state{0xffffffffu};
  /// Blocks finished in the current phase (the leader waits for all of them).
  alignas(64) std::atomic<long> done{0};
  /// The current phase: f(context, block). Written before the state that publishes them.
  std::atomic<void (*)(void*, long)> function{nullptr};
  std::atomic<void*> context{nullptr};
  /// The leader is done: helpers return from serve().
  std::atomic<bool> finished{false};
};

/// One thread's view of the team. The leader (thread 0) calls for_blocks, serial and sync; the
/// others call serve() once, which returns when the leader calls finish().
class BlockTeam {
 public:
  BlockTeam(TeamShared& shared, int thread, long blocks)
      : m_shared(shared), m_thread(thread), m_blocks(blocks) {}
  /// Leader: f(block) for every block, shared out among the leader and the helpers; returns
  /// when every block is done (and everything the blocks wrote is visible).
  template <class F>
  void for_blocks(F&& f) {
    using Fn = std::remove_reference_t<F>;
    m_shared.done.store(0, std::memory_order_relaxed);
    m_shared.context.store(const_cast<void*>(static_cast<const void*>(&f)),
                           std::memory_order_relaxed);
    m_shared.function.store([](void* c, long b) { (*static_cast<Fn*>(c))(b); },
                            std::memory_order_relaxed);
    const std::uint64_t generation = ++m_generation;
    m_shared.state.store(generation << 32, std::memory_order_release);
    m_shared.state.notify_all();
    work(m_shared, generation, m_blocks);
    for (int i = 0;; ++i) {
      const long d = m_shared.done.load(std::memory_order_acquire);
      if (d == m_blocks) break;
      if (i >= kSpin) m_shared.done.wait(d, std::memory_order_acquire);
    }
  }
  /// Leader: nothing to wait for (the helpers only ever run posted blocks).
  void sync() {}
  /// Leader: a serial part of the step.
  template <class F>
  void serial(F&& f) {
    f();
  }
  bool leader() const { return m_thread == 0; }
  /// Leader: lets the helpers return from serve().
  void finish() {
    m_shared.finished.store(true, std::memory_order_release);
    m_shared.state.store((m_generation + 1) << 32 | 0xffffffffu, std::memory_order_release);
    m_shared.state.notify_all();
  }
  /// Helper: runs the posted phases' blocks until the leader calls finish().
  void serve() {
    for (int i = 0;; ++i) {
      const std::uint64_t s = m_shared.state.load(std::memory_order_acquire);
      // finish() sets `finished` before its state: seeing that state means seeing `finished`
      if (m_shared.finished.load(std::memory_order_acquire)) return;
      if (static_cast<long>(s & 0xffffffffu) < m_blocks) {
        work(m_shared, s >> 32, m_blocks);
        i = 0;
        continue;
      }
      // a short spin (a few microseconds) catches the next phase without a system call
      if (i >= kSpin) m_shared.state.wait(s, std::memory_order_acquire);
    }
  }

 private:
  static constexpr int kSpin = 2000;
  /// Claims and runs blocks of phase `generation` until none is left.
  static void work(TeamShared& shared, std::uint64_t generation, long blocks) {
    std::uint64_t s = shared.state.load(std::memory_order_acquire);
    while ((s >> 32) == generation && static_cast<long>(s & 0xffffffffu) < blocks) {
      // read before the claim: valid for this generation if the claim succeeds (the phase
      // cannot end, nor the next be posted, while one of its blocks is unclaimed)
      void (*f)(void*, long) = shared.function.load(std::memory_order_relaxed);
      void* c = shared.context.load(std::memory_order_relaxed);
      if (!shared.state.compare_exchange_weak(s, s + 1, std::memory_order_acq_rel,
                                              std::memory_order_acquire))
        continue;
      f(c, static_cast<long>(s & 0xffffffffu));
      if (shared.done.fetch_add(1, std::memory_order_acq_rel) + 1 == blocks)
        shared.done.notify_one();
      s = shared.state.load(std::memory_order_acquire);
    }
  }
  TeamShared& m_shared;
  int m_thread;
  long m_blocks;
  std::uint64_t m_generation = 0;
};

}  // namespace thaw::sim
