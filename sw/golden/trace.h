#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "golden/records.h"

namespace lancer::fx {

// What a traversal unit (grid, octree, ...) did for one ray: the structure
// elements it entered, in order, the ray-triangle tests it issued, and its
// closest hit. The driver compares these bit for bit between models.
struct TraversalTrace {
  std::vector<uint32_t> visits;    // cell ids (grid) or node indices (octree), in visiting order
  uint64_t tests = 0;              // ray-primitive tests issued
  uint64_t quadricTests = 0;       // of which ray-quadric (the rest ray-triangle)
  std::optional<IsectResult> hit;  // closest hit (closerResult order)
  bool operator==(const TraversalTrace&) const = default;
};

// What a treelet schedule moves for rays (docs/scheduling.md, "The treelet
// schedule"): how often their walks enter an interior node in another treelet
// block than the one they are in, how many of those crossings suspend the walk
// (a suspension and a resumption each: the stack fits the unit's suspend
// window), and the state moved at those (the unit's own measure of it:
// bvhSuspendedBits).
struct TreeletCrossings {
  uint64_t rays = 0;
  uint64_t crossings = 0;
  uint64_t suspensions = 0;  // of the crossings, those with the stack within the window
  uint64_t stateBits = 0;    // summed over the suspensions
  TreeletCrossings& operator+=(const TreeletCrossings& o) {
    *this = {rays + o.rays, crossings + o.crossings, suspensions + o.suspensions, stateBits + o.stateBits};
    return *this;
  }
  bool operator==(const TreeletCrossings&) const = default;
};

// A traversal unit's result record, its fields unpacked in traversalResFields
// order (ray id, elements visited, tests, quadric tests, hit, prim id, t_num,
// det, u_num, v_num), into `trace` of the ray whose own id is `rayId`: the
// test counts and the closest hit. Returns the elements visited, which the
// caller checks against the visit stream. One decoder for every model of
// every unit.
inline uint32_t takeTraversalResult(const std::array<u128, 10>& fields, uint32_t rayId, TraversalTrace& trace) {
  trace.tests = uint64_t(fields[2]);
  trace.quadricTests = uint64_t(fields[3]);
  if (fields[4]) {
    IsectResult hit;
    hit.rayId = rayId;
    hit.primId = uint32_t(fields[5]);
    hit.hit = true;
    hit.tNum = fields[6];
    hit.det = fields[7];
    hit.uNum = fields[8];
    hit.vNum = fields[9];
    trace.hit = hit;
  }
  return uint32_t(fields[1]);
}

// The closest hit so far as the first kWalkHitFields values of a walk record
// (walkRecordFields), and back for the ray whose own id is `rayId`.
inline void putWalkHit(const std::optional<IsectResult>& hit, std::span<u128> values) {
  const IsectResult h = hit.value_or(IsectResult{});
  const std::array<u128, kWalkHitFields> v{u128(hit ? 1 : 0), u128(h.primId), h.tNum, h.det, h.uNum, h.vNum};
  std::copy(v.begin(), v.end(), values.begin());
}
inline std::optional<IsectResult> walkHitOf(std::span<const u128> v, uint32_t rayId) {
  if (v[0] == 0) return std::nullopt;
  return IsectResult{.rayId = rayId, .primId = uint32_t(v[1]), .hit = true, .tNum = v[2], .det = v[3],
                     .uNum = v[4], .vNum = v[5]};
}

}  // namespace lancer::fx
