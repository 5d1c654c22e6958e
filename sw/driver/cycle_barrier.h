#pragma once

// The barrier that ends each cycle of a chip clocked on several host threads
// (verilator_traversal_run.h): the last thread to arrive runs the cycle's
// shared part alone (the memory system, the dispatcher), then every thread
// goes on. A cycle of a unit is a few microseconds of host time, less than a
// futex wake-up, so the threads first spin for a while (the usual wait is
// short when each thread has a core) and only then sleep on the generation
// counter (a loaded machine, where spinning would steal the core the last
// thread needs).

#include <atomic>
#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace lancer {

class CycleBarrier {
 public:
  explicit CycleBarrier(int threads) : threads_(threads) {}

  // Every thread calls it once a cycle; exactly one (the last to arrive) runs
  // `last` before any returns.
  template <class Last>
  void arriveAndWait(Last&& last) {
    const uint32_t generation = generation_.load(std::memory_order_acquire);
    if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == threads_) {
      last();
      arrived_.store(0, std::memory_order_relaxed);
      generation_.store(generation + 1, std::memory_order_release);
      generation_.notify_all();
      return;
    }
    for (int spin = 0; spin < kSpins; ++spin) {
      if (generation_.load(std::memory_order_acquire) != generation) return;
      pause();
    }
    while (generation_.load(std::memory_order_acquire) == generation) {
      generation_.wait(generation, std::memory_order_acquire);
    }
  }

 private:
  static constexpr int kSpins = 4000;  // about 10-40 us of pause instructions
  static void pause() {
#if defined(__x86_64__) || defined(__i386__)
    _mm_pause();
#endif
  }

  const int threads_;
  std::atomic<int> arrived_{0};
  std::atomic<uint32_t> generation_{0};
};

}  // namespace lancer
