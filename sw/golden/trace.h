#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "golden/records.h"

namespace lancer::fx {

// What a traversal unit (grid, octree, ...) did for one ray: the structure
// elements it entered, in order, the ray-triangle tests it issued, and its
// closest hit. The driver compares these bit for bit between models.
struct TraversalTrace {
  std::vector<uint32_t> visits;    // cell ids (grid) or node indices (octree), in visiting order
  uint64_t tests = 0;              // ray-triangle tests issued
  std::optional<IsectResult> hit;  // closest hit (closerResult order)
  bool operator==(const TraversalTrace&) const = default;
};

}  // namespace lancer::fx
