#pragma once

// The octree unit's formats and records (docs/octree-unit.md), as
// golden/formats.h and golden/records.h are the shared ones: gen_rt_pkg emits
// them into rt_pkg through the unit's descriptor (kPkgParams, kRecords).

#include <array>
#include <bit>

#include "golden/records.h"

namespace lancer::fx {

// ---- Octree stepping unit (docs/octree-unit.md) ----------------------------------
// The root is the lattice cube [0, 2^P]; a node at depth k has side 2^(P-k), so
// every mid-plane of a node of side >= 2 is an integer and the parametric
// traversal's halvings tm = (t0 + t1) / 2 are exact: depth P is the limit.
inline constexpr int kOctreeMaxDepth = kPosBits;
// Plane parameters over the common denominator prod(|d_b|, active b):
// T = (plane - o') * prod(|d_b|, b != a), |plane - o'| <= 2^P, prod < 2^(2(D-1))
// ............................................................. P+2D signed
inline constexpr int kOctreeTBits = kPosBits + 2 * kDirBits;
// Common denominator C = prod(|d_a|, active a) < 2^(3(D-1)) ....... 3D-3 unsigned
inline constexpr int kOctreeCommonBits = 3 * (kDirBits - 1);
// The walk holds one entry per level, root included: at most P + 1.
inline constexpr int kOctreeStackDepth = kOctreeMaxDepth + 1;
// A child group: an interior node's eight children, read as one memory word.
inline constexpr int kOctreeChildren = 8;

// ---- octree_node_t: one entry of the octree unit's node table ---------------------
inline constexpr FieldSpec kOctreeNodeFields[] = {
    {"leaf", 1, 1, false, "1: a leaf; 0: an interior node"},
    {"count", 31, 1, false, "leaf: triangles listed; interior: 0"},
    {"first", 32, 1, false, "leaf: first index-list entry; interior: node index of child 0"},
};
// ---- octree_visit_t: one node entered, on the unit's trace stream; octree_res_t ----
inline constexpr auto kOctreeVisitFields = traversalVisitFields("node_id", 32, "node index in the node table");
inline constexpr auto kOctreeResFields = traversalResFields("nodes", "nodes entered");

// ---- The treelet schedule: a walk set aside and resumed (docs/scheduling.md) -----
// With suspension on, a walk about to descend into an interior node whose
// child group lies in another treelet block than the one it is in (block =
// node-table index >> block shift) leaves the unit with its state, when its
// stack holds at most kOctreeSuspendLevels levels; deeper, it goes on into
// that block. A walk going back up (the refill of a parent's group after a
// pop) never stops: the upper groups are every ray's, and stopping there as
// well doubled the suspensions for the same DRAM traffic (docs/scheduling.md).
// The window bounds the record, as the BVH's does.
inline constexpr int kOctreeSuspendLevels = 8;
inline constexpr int kOctreeDepthBits = std::bit_width(unsigned(kOctreeMaxDepth));  // 0 .. P levels
inline constexpr int kOctreeBlockShiftBits = 5;  // a block of 2^0 .. 2^31 entries
inline constexpr int kOctreeChildBits = 3;       // a child's number, 4x + 2y + z (mirrored)
// ---- octree_walk_t: a suspended walk: its closest hit so far, the group it reads
// first, the node's parameters, its stack ----------------------------------------------
inline constexpr auto kOctreeWalkFields = walkRecordFields(std::array<FieldSpec, 6>{{
    {"group", 32, 1, false, "the entered node's child group (node index), read first on resuming, then descended into"},
    {"depth", kOctreeDepthBits, 1, false, "stack levels, 0 .. OCTREE_SUSPEND_LEVELS"},
    {"t0", kOctreeTBits, 3, true, "the node's entry plane parameters, [0]=x (an axis the ray never crosses: 0)"},
    {"t1", kOctreeTBits, 3, true, "its exit plane parameters"},
    {"stack_first", 32, kOctreeSuspendLevels, false, "level k's child-group base (bottom first; k < depth)"},
    {"stack_child", kOctreeChildBits, kOctreeSuspendLevels, false, "which of its children the walk is in (mirrored)"},
}});
inline constexpr int kOctreeWalkBits = recordBits(kOctreeWalkFields);

inline constexpr RecordSpec kOctreeRecords[] = {
    {"octree_node_t", "OCTREE_NODE_W", "an octree node table entry", kOctreeNodeFields},
    {"octree_walk_t", "OCTREE_WALK_W", "an octree walk set aside (treelet schedule)", kOctreeWalkFields},
    {"octree_visit_t", "OCTREE_VISIT_W", "an octree unit node step", kOctreeVisitFields},
    {"octree_res_t", "OCTREE_RESULT_W", "an octree unit ray result", kOctreeResFields},
};
inline constexpr int kOctreeNodeBits = recordBits(kOctreeNodeFields);
static_assert(kMemAddrBits <= 31, "a leaf's count (up to the index list's size) must fit octree_node_t.count");
static_assert(kOctreeNodeBits == 64, "a node is one 64-bit word; a child group one 512-bit line");

// rt_octree_setup's register stages: a ray accepted at edge t loads its slot
// at edge t + 1 + kOctreeSetupLatency (one multiplication deep each: |d| and
// o', the pairs, the root's planes). The RTL builds these stages; the SystemC
// shell model carries the ray through as many.
inline constexpr int kOctreeSetupLatency = 3;

// What rt_pkg holds of the octree's formats (before its records' widths) and
// of its latencies (after them).
inline constexpr PackageParam kOctreeFormatParams[] = {
    {"OCTREE_MAX_DEPTH", kOctreeMaxDepth}, {"OCTREE_STACK_DEPTH", kOctreeStackDepth},
    {"OCTREE_T_W", kOctreeTBits},          {"OCTREE_COMMON_W", kOctreeCommonBits},
    {"OCTREE_CHILDREN", kOctreeChildren},
    {"OCTREE_SUSPEND_LEVELS", kOctreeSuspendLevels}, {"OCTREE_DEPTH_W", kOctreeDepthBits},
    {"OCTREE_BLOCK_SHIFT_W", kOctreeBlockShiftBits},
};
inline constexpr PackageParam kOctreeLatencies[] = {{"OCTREE_SETUP_LATENCY", kOctreeSetupLatency}};

}  // namespace lancer::fx
