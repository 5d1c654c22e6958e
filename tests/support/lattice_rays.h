#pragma once

// Lattice rays for the tests of the fixed-point models.

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>

#include "golden/formats.h"

namespace lancer::test {

// A direction from `from` toward `to`, quantized as the lattice rays are: its
// dominant component +-kDirMax, the others rounded to nearest (+x for from = to).
inline std::array<int64_t, 3> latticeDirectionTo(const std::array<int64_t, 3>& from, const std::array<int64_t, 3>& to) {
  std::array<int64_t, 3> v{}, d{};
  int64_t largest = 0;
  for (size_t k = 0; k < 3; ++k) {
    v[k] = to[k] - from[k];
    largest = std::max(largest, std::abs(v[k]));
  }
  if (largest == 0) return {fx::kDirMax, 0, 0};
  for (size_t k = 0; k < 3; ++k) d[k] = (2 * v[k] * fx::kDirMax + (v[k] < 0 ? -largest : largest)) / (2 * largest);
  return d;
}

}  // namespace lancer::test
