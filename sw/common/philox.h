#pragma once

// Philox4x32-10 (Salmon, Moraes, Dror and Shaw, "Parallel random numbers: as
// easy as 1, 2, 3", SC 2011): a counter-based generator. Its output is a pure
// function of a 128-bit counter and a 64-bit key, ten rounds of a
// multiply-hi/lo Feistel network, so any number of the stream is computed
// directly, on any thread, in any order: what makes the integrators' rays
// independent of the model, the unit count, the dispatch order, the threads
// and the shard (docs/incoherent.md). Checked against the Random123 library's
// known-answer vectors (tests/effects/integrators_test.cpp).

#include <array>
#include <cstdint>

namespace lancer {

using PhiloxCounter = std::array<uint32_t, 4>;
using PhiloxKey = std::array<uint32_t, 2>;

constexpr PhiloxCounter philox4x32_10(PhiloxCounter c, PhiloxKey k) {
  constexpr uint32_t kMul0 = 0xD2511F53u, kMul1 = 0xCD9E8D57u;    // the round multipliers
  constexpr uint32_t kWeyl0 = 0x9E3779B9u, kWeyl1 = 0xBB67AE85u;  // the key schedule's increments
  for (int round = 0; round < 10; ++round) {
    if (round > 0) {
      k[0] += kWeyl0;
      k[1] += kWeyl1;
    }
    const uint64_t p0 = uint64_t(kMul0) * c[0];
    const uint64_t p1 = uint64_t(kMul1) * c[2];
    c = {uint32_t(p1 >> 32) ^ c[1] ^ k[0], uint32_t(p1), uint32_t(p0 >> 32) ^ c[3] ^ k[1], uint32_t(p0)};
  }
  return c;
}

// A uniform float in [0, 1) from a 32-bit word: its top 24 bits, exactly.
constexpr float unitFloat(uint32_t word) { return float(word >> 8) * 0x1.0p-24f; }

}  // namespace lancer
