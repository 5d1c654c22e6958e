#pragma once

// The scaffolding the host-speed benches (grid_models_bench, isect_models_bench)
// share: the clocks of a sample, medians, and timed rounds whose model order
// rotates so that load from other work hits all models alike.

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <vector>

namespace lancer::bench {

inline double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// The median of `v`; 0 for none.
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

// Wall clock and the calling thread's CPU time of one sample, in seconds.
struct Sample {
  double wall = 0, cpu = 0;
};

template <class F>
Sample timeSample(F&& work) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu0 = threadCpuSeconds();
  work();
  Sample s;
  s.cpu = threadCpuSeconds() - cpu0;
  s.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

// `rounds` timed rounds over `models` models: each round calls sample(m) once
// for every model m, starting one model later than the round before.
template <class F>
void rotatedRounds(int rounds, size_t models, F&& sample) {
  for (int round = 0; round < rounds; ++round) {
    for (size_t i = 0; i < models; ++i) sample((i + size_t(round)) % models);
  }
}

}  // namespace lancer::bench
