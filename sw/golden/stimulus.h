#pragma once

#include <algorithm>
#include <cstdint>
#include <deque>
#include <random>

namespace lancer::fx {

// The random stimulus every testbench and memory model shares, so that the
// same seed gives the same cycles in every model (C++ Verilated devices,
// SystemC testbenches and memories).

// Bernoulli draws that cost nothing (no draw) when the probability is zero.
class Coin {
 public:
  Coin(double p, std::mt19937_64& rng) : threshold_(thresholdFor(p)), rng_(rng) {}
  bool operator()() { return threshold_ != 0 && rng_() < threshold_; }
  // rng() < thresholdFor(p) happens with probability p; 0 for p <= 0 (or NaN).
  static uint64_t thresholdFor(double p) {
    if (!(p > 0.0)) return 0;
    if (p >= 1.0) return ~uint64_t(0);
    return uint64_t(p * 18446744073709551616.0);  // p * 2^64
  }

 private:
  uint64_t threshold_;
  std::mt19937_64& rng_;
};

// The timing of one read port of the traversal units' memory (cell or node
// table, index list, triangle table), shared by every testbench and memory
// model (C++ Verilated devices, SystemC memories) so that for the same latency,
// jitter and seed all of them answer in the same cycles. The port accepts one
// request per cycle (req_ready is always 1). A request accepted in cycle c is
// answered in cycle c + latency + U(0..jitter) (one mt19937_64 draw per
// request, only if jitter > 0), but never before or in the same cycle as the
// port's previous response: in order, at most one response per cycle.
class MemoryReadPort {
 public:
  MemoryReadPort() = default;
  MemoryReadPort(int latency, int jitter, uint64_t seed) { restart(latency, jitter, seed); }

  void restart(int latency, int jitter, uint64_t seed) {
    latency_ = latency;
    jitter_ = jitter;
    rng_.seed(seed);
    pending_.clear();
    lastDue_ = 0;
  }
  void request(uint64_t cycle, uint32_t addr, uint32_t tag) {
    uint64_t due = cycle + uint64_t(latency_);
    if (jitter_ > 0) due += rng_() % uint64_t(jitter_ + 1);
    due = std::max(due, lastDue_ + 1);
    lastDue_ = due;
    pending_.push_back({due, addr, tag});
  }
  // The request answered in `cycle`, if any (removed from the port).
  bool respond(uint64_t cycle, uint32_t& addr, uint32_t& tag) {
    if (pending_.empty() || pending_.front().due > cycle) return false;
    addr = pending_.front().addr;
    tag = pending_.front().tag;
    pending_.pop_front();
    return true;
  }
  bool idle() const { return pending_.empty(); }

 private:
  struct Pending {
    uint64_t due;
    uint32_t addr, tag;
  };
  int latency_ = 1, jitter_ = 0;
  std::mt19937_64 rng_;
  std::deque<Pending> pending_;
  uint64_t lastDue_ = 0;
};

}  // namespace lancer::fx
