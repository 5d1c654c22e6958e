#pragma once

// Exact 256-bit products for the comparisons of fractions the hardware makes
// by cross-multiplication (hit ordering, the grid's exit test).

#include "golden/formats.h"

namespace lancer::fx {

struct U256 {
  u128 hi = 0, lo = 0;
  bool operator<(const U256& o) const { return hi < o.hi || (hi == o.hi && lo < o.lo); }
  bool operator==(const U256& o) const = default;
};

inline U256 mul256(u128 a, u128 b) {
  const u128 mask = ~uint64_t(0);
  const u128 a0 = a & mask, a1 = a >> 64, b0 = b & mask, b1 = b >> 64;
  const u128 p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
  const u128 middle = (p00 >> 64) + (p01 & mask) + (p10 & mask);
  return {p11 + (p01 >> 64) + (p10 >> 64) + (middle >> 64), (middle << 64) | (p00 & mask)};
}

}  // namespace lancer::fx
