#pragma once

// The BVH unit's formats and records (docs/bvh-unit.md), as golden/formats.h
// and golden/records.h are the shared ones: gen_rt_pkg emits them into rt_pkg
// through the unit's descriptor (kPkgParams, kRecords).

#include <array>
#include <bit>

#include "golden/records.h"

namespace lancer::fx {

// ---- BVH traversal unit (docs/bvh-unit.md) ------------------------------------------
// A binary BVH: a node read returns both children's boxes, tested side by side.
inline constexpr int kBvhWidth = 2;
// Child planes are kBvhPlaneBits-bit steps of 2^shift from the node's corner
// `base` (per axis), rounded outwards: lo = base + (q_lo << shift) <= the
// child's lowest vertex, hi = base + (q_hi << shift) >= its highest.
inline constexpr int kBvhPlaneBits = 8;
inline constexpr int kBvhPlaneMax = (1 << kBvhPlaneBits) - 1;
// shift: 0 .. P - kBvhPlaneBits + 1 (a node's extent is below 2^P).
inline constexpr int kBvhShiftBits = std::bit_width(unsigned(kPosBits));
// A leaf lists up to 2^kBvhCountBits - 1 triangles.
inline constexpr int kBvhCountBits = 8;
inline constexpr int kBvhMaxLeafSize = (1 << kBvhCountBits) - 1;
// The per-ray stack: one entry per level below the root at most (the walk
// pushes the far child of a node whose children it both enters), so a tree of
// kBvhStackDepth + 1 levels never overflows it; deeper images are refused.
inline constexpr int kBvhStackDepth = 32;
inline constexpr int kBvhMaxLevels = kBvhStackDepth + 1;
// Plane parameters over the common denominator C = prod(|d_a|, active a):
// T = (plane' - o') * prod(|d_b|, active b != a). A reconstructed plane lies in
// [0, 2^P + 2^shift) and o' in [0, 2^P], so |plane' - o'| < 2^(P+1); the product
// below 2^(2(D-1)): P + 2D signed bits ........................................
inline constexpr int kBvhTBits = kPosBits + 2 * kDirBits;
// A child's entry parameter max(t_min, 0) * C, unsigned ......................
inline constexpr int kBvhEntryBits = kBvhTBits - 1;
// C = prod(|d_a|, active a) < 2^(3(D-1)) ................................ 3D-3 unsigned
inline constexpr int kBvhCommonBits = 3 * (kDirBits - 1);
// A visit names an interior node by its node-table index and a leaf by this
// bit set over its first index-list entry.
inline constexpr uint32_t kBvhLeafVisit = uint32_t(1) << 31;

// ---- bvh_ref_t: a child as its parent names it (and the root, on cfg_root_i) --------
inline constexpr FieldSpec kBvhRefFields[] = {
    {"leaf", 1, 1, false, "1: a leaf; 0: an interior node"},
    {"count", kBvhCountBits, 1, false, "leaf: triangles listed; interior: 0"},
    {"first", 32, 1, false, "leaf: first index-list entry; interior: node-table index"},
};
inline constexpr int kBvhRefBits = recordBits(kBvhRefFields);
// ---- bvh_node_t: one entry of the node table, an interior node's two children -------
inline constexpr FieldSpec kBvhNodeFields[] = {
    {"base", kPosBits, 3, false, "the node's lowest corner, [0]=x"},
    {"shift", kBvhShiftBits, 3, false, "plane step 2^shift per axis"},
    {"lo", kBvhPlaneBits, 6, false, "child c's lower plane on axis a: element 3c + a"},
    {"hi", kBvhPlaneBits, 6, false, "child c's upper plane on axis a: element 3c + a"},
    {"leaf", 1, 2, false, "child c: as bvh_ref_t"},
    {"count", kBvhCountBits, 2, false, "child c: as bvh_ref_t"},
    {"first", 32, 2, false, "child c: as bvh_ref_t"},
};
// ---- bvh_visit_t: one node entered, on the unit's trace stream; bvh_res_t ----------
inline constexpr auto kBvhVisitFields =
    traversalVisitFields("node_id", 32, "interior: node-table index; leaf: 2^31 + first index-list entry");
inline constexpr auto kBvhResFields = traversalResFields("nodes", "nodes entered");

// ---- The treelet schedule: a walk set aside and resumed (docs/scheduling.md) -----
// With suspension on (cfg_suspend_i), a walk about to enter an interior node of
// another treelet block than the one it is in (block = node-table index >>
// cfg_block_shift_i) leaves the unit, its state on the result port
// (res_suspended_o, res_walk_o), when its stack holds at most
// kBvhSuspendEntries entries; with more it goes on into that block. A
// resumed ray comes back on the ray port with its state (ray_resume_i,
// ray_walk_i) and enters that node first. The window bounds the record: a
// suspension carries the stack's bottom kBvhSuspendEntries entries, not 32.
inline constexpr int kBvhSuspendEntries = 8;
inline constexpr int kBvhSpBits = std::bit_width(unsigned(kBvhStackDepth));  // 0 .. kBvhStackDepth
inline constexpr int kBvhBlockShiftBits = 5;                                  // a block of 2^0 .. 2^31 entries
// ---- bvh_walk_t: a suspended walk: its closest hit so far, the node it enters
// next, its stack --------------------------------------------------------------------
inline constexpr auto kBvhWalkFields = walkRecordFields(std::array<FieldSpec, 5>{{
    {"next_ref", kBvhRefBits, 1, false, "the node entered on resuming (bvh_ref_t; box test passed, not culled)"},
    {"next_entry", kBvhEntryBits, 1, false, "its entry parameter"},
    {"sp", kBvhSpBits, 1, false, "stack entries, 0 .. BVH_SUSPEND_ENTRIES"},
    {"stack_ref", kBvhRefBits, kBvhSuspendEntries, false, "stack entry k (bottom first; k < sp): bvh_ref_t"},
    {"stack_entry", kBvhEntryBits, kBvhSuspendEntries, false, "its entry parameter"},
}});

inline constexpr RecordSpec kBvhRecords[] = {
    {"bvh_ref_t", "BVH_REF_W", "a BVH child reference", kBvhRefFields},
    {"bvh_node_t", "BVH_NODE_W", "a BVH node table entry", kBvhNodeFields},
    {"bvh_walk_t", "BVH_WALK_W", "a BVH walk set aside (treelet schedule)", kBvhWalkFields},
    {"bvh_visit_t", "BVH_VISIT_W", "a BVH unit node step", kBvhVisitFields},
    {"bvh_res_t", "BVH_RESULT_W", "a BVH unit ray result", kBvhResFields},
};
inline constexpr int kBvhNodeBits = recordBits(kBvhNodeFields);
inline constexpr int kBvhWalkBits = recordBits(kBvhWalkFields);
static_assert(kMemAddrBits <= 31, "a leaf's visit id sets bit 31 over an index-list entry");

// rt_bvh_setup's register stages (docs/bvh-unit.md): |d| and o', the pair
// products, the common denominator.
inline constexpr int kBvhSetupLatency = 3;
// rt_bvh_box's register stages: a node response in cycle r is answered (both
// children's hits and entries) to its slot in cycle r + kBvhBoxLatency: the
// planes less the origin, the twelve products, the intervals, the hits and
// the order.
inline constexpr int kBvhBoxLatency = 4;

// What rt_pkg holds of the BVH's formats (before its records' widths) and of
// its latencies (after them).
inline constexpr PackageParam kBvhFormatParams[] = {
    {"BVH_WIDTH", kBvhWidth},        {"BVH_PLANE_W", kBvhPlaneBits},      {"BVH_SHIFT_W", kBvhShiftBits},
    {"BVH_COUNT_W", kBvhCountBits},  {"BVH_STACK_DEPTH", kBvhStackDepth}, {"BVH_T_W", kBvhTBits},
    {"BVH_ENTRY_W", kBvhEntryBits},  {"BVH_COMMON_W", kBvhCommonBits},
    {"BVH_SUSPEND_ENTRIES", kBvhSuspendEntries}, {"BVH_SP_W", kBvhSpBits},
    {"BVH_BLOCK_SHIFT_W", kBvhBlockShiftBits},
};
inline constexpr PackageParam kBvhLatencies[] = {
    {"BVH_SETUP_LATENCY", kBvhSetupLatency},
    {"BVH_BOX_LATENCY", kBvhBoxLatency},
};

}  // namespace lancer::fx
