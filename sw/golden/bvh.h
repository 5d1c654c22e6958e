#pragma once

// Bit-accurate model of the BVH traversal unit (rt_bvh): the memory image the
// driver builds from the binned-SAH tree (common/sah.h, the reference's
// builder) and the walk that defines which nodes each ray enters and which hit
// it returns. docs/bvh-unit.md has the derivation.

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include "golden/bvh_formats.h"
#include "golden/lattice.h"
#include "golden/primitives.h"
#include "golden/records.h"
#include "golden/trace.h"

namespace lancer::fx {

// A child as its parent names it (bvh_ref_t); the root's is a configuration input.
struct BvhRef {
  bool leaf = true;
  uint32_t count = 0;  // leaf: triangles; interior: 0
  uint32_t first = 0;  // leaf: first index-list entry; interior: node-table index
  bool operator==(const BvhRef&) const = default;
  // The visit record's id of this node.
  uint32_t visitId() const { return leaf ? (kBvhLeafVisit | first) : first; }
};

// A child's plane in its parent's frame: base + (step << shift), on the
// lattice (an upper plane may exceed kPosMax by less than 2^shift).
inline int64_t bvhPlane(int64_t base, uint32_t step, int shift) { return base + (int64_t(step) << shift); }

// An interior node (bvh_node_t): its children's boxes in its own frame.
struct BvhNode {
  std::array<int64_t, 3> base{};  // the node's lowest corner
  std::array<int, 3> shift{};     // plane step 2^shift per axis
  std::array<std::array<uint32_t, 3>, kBvhWidth> lo{}, hi{};  // [child][axis] plane steps
  std::array<BvhRef, kBvhWidth> child{};
  bool operator==(const BvhNode&) const = default;
  // Child c's box, planes on the lattice (hi may exceed kPosMax by less than 2^shift).
  std::array<int64_t, 3> childLo(int c) const;
  std::array<int64_t, 3> childHi(int c) const;
};

struct BvhImage {
  int leafSize = 0;
  BvhRef root;                       // the tree's root (cfg_root_i)
  std::vector<BvhNode> nodes;        // interior nodes; the root, if interior, is node 0
  std::vector<uint32_t> indices;     // primitive entries (golden/primitives.h), leaf by leaf
  std::vector<QTriangle> triangles;  // by place
  std::vector<QQuadric> quadrics;    // by place
  int depth = 0;                     // levels, root = 1
  size_t leaves = 0;
  // The treelet layout (layoutBvhTreelets); 0 treeletNodes: the depth-first layout.
  uint32_t treeletNodes = 0;         // node-table entries of a treelet block (a power of two)
  size_t treelets = 0;               // connected subtrees, packed into the blocks
  size_t paddingNodes = 0;           // unused entries inside the blocks (never read)
  // The treelet block of interior node `index` (one block without the layout).
  uint32_t blockOf(uint32_t index) const { return treeletNodes ? index / treeletNodes : 0; }
};

inline constexpr int kDefaultBvhLeafSize = 4;

// Builds the image from the binned-SAH tree over the primitives' lattice boxes
// (a triangle's integer bounding box, a quadric's record bounds): each
// interior node's two children's boxes quantized outwards in its frame.
// Throws InputError for a leaf size outside 1..kBvhMaxLeafSize, or an image
// that does not fit kMemAddrBits.
BvhImage buildBvhImage(std::vector<QTriangle> triangles, int leafSize, std::vector<QQuadric> quadrics = {});

// The treelet layout (docs/scheduling.md, "The treelet layout"): the tree
// cut greedily into treelets of at most `blockNodes` interior nodes (Aila &
// Karras 2010: from a treelet's root, the frontier child with the largest
// surface area joins until the treelet is full; the children left over root
// new treelets), packed in depth-first order into aligned blocks of
// `blockNodes` node-table entries (a block may hold several small treelets;
// entries left over are padding, never read), each treelet's nodes in
// depth-first order inside its block. The triangle and quadric tables are put
// in leaf order (the index list then counts 0, 1, 2, ... per kind), so a
// leaf's primitives are adjacent. Every ray walks the same nodes in the same order to the same hit;
// only the node-table indices and the triangles' places change.
// `blockNodes` must be a power of two (InputError otherwise).
void layoutBvhTreelets(BvhImage& image, uint32_t blockNodes);

// The BVH walk's state when it is suspended (TreeletCrossings), as a ray
// queue holds it: the ray record and its bvh_walk_t with `stackEntries`
// stack entries (the unused ones of the window are not stored).
inline constexpr int kBvhStackEntryBits = kBvhRefBits + kBvhEntryBits;  // {reference, entry parameter}
constexpr int bvhSuspendedBits(size_t stackEntries) {
  return kIsectRayBits + kBvhWalkBits - kBvhStackEntryBits * (kBvhSuspendEntries - int(stackEntries));
}
// The crossings of `ray`'s walk over a treelet layout (none without one).
TreeletCrossings bvhTreeletCrossings(const BvhImage& image, const QRay& ray);

// Throws InputError, naming the first region that overflows, unless the node
// table, the index list and the primitive tables each fit `addrBits` address
// bits. buildBvhImage checks the unit's kMemAddrBits.
void checkBvhImageFits(const BvhImage& image, int addrBits = kMemAddrBits);

// The smallest shift whose kBvhPlaneBits steps cover `extent`.
int bvhShiftFor(int64_t extent);
// Child plane steps of [lo, hi] in a frame (base, shift), rounded outwards.
uint32_t bvhPlaneDown(int64_t plane, int64_t base, int shift);
uint32_t bvhPlaneUp(int64_t plane, int64_t base, int shift);

// The per-ray setup of the unit: the mirrored ray (o' = 2^P - o for a negative
// component), its pair products and common denominator. Multiplications only.
struct BvhRaySetup : MirroredRay {
  static BvhRaySetup setup(const QRay& ray) { return {MirroredRay::of(ray)}; }
};

// The ray-box test of one child box: exact over the lattice planes, closed
// boxes. The ray enters iff max(T0) <= min(T1) over the active axes, min(T1) > 0
// (some point of the box at t > 0), and the origin lies within the box on every
// axis the ray does not cross. `entry` = max(t_min, 0) * common.
struct BoxHit {
  bool hit = false;
  u128 entry = 0;
  bool operator==(const BoxHit&) const = default;
};
// A plane parameter T (kBvhTBits signed bits), in a machine word where the
// formats allow: the box test runs on every node a walk enters.
using BvhParam = std::conditional_t<(kBvhTBits <= 64), int64_t, i128>;
inline BoxHit boxTest(const BvhRaySetup& ray, const std::array<int64_t, 3>& lo, const std::array<int64_t, 3>& hi) {
  static_assert(2 * (kDirBits - 1) < 63, "a pair product (two |d|) fits a word");
  BvhParam tMin = 0, tMax = 0;  // max(T0), min(T1) over the active axes
  bool any = false;
  for (int a = 0; a < 3; ++a) {
    // Mirrored: the box [lo, hi] becomes [2^P - hi, 2^P - lo].
    const int64_t l = ray.mirrored(a) ? kLatticeSide - hi[a] : lo[a];
    const int64_t h = ray.mirrored(a) ? kLatticeSide - lo[a] : hi[a];
    if (!ray.active[a]) {
      // The ray stays in the plane x_a = o_a: inside the slab for all t, or never.
      if (ray.origin[a] < l || ray.origin[a] > h) return {};
      continue;
    }
    const BvhParam pair = BvhParam(int64_t(ray.pair[a]));
    const BvhParam t0 = BvhParam(l - ray.origin[a]) * pair, t1 = BvhParam(h - ray.origin[a]) * pair;
    tMin = any ? std::max(tMin, t0) : t0;
    tMax = any ? std::min(tMax, t1) : t1;
    any = true;
  }
  if (!(tMin <= tMax && tMax > 0)) return {};
  return BoxHit{true, u128(std::max<BvhParam>(tMin, 0))};
}

// The cull rule of a node about to be entered: the closest hit so far (or the
// segment end) lies before it, t_bound <= (entry - 1) / common. Entry 0 is
// never culled. Exact (256-bit products), the shell's exit test with
// exit = entry - 1.
bool culledBy(const IsectResult& bound, u128 entry, const BvhRaySetup& ray);

// The reference behaviour of the unit for one ray. Throws std::logic_error if
// the stack would overflow (an image deeper than kBvhMaxLevels: checkImage
// refuses those).
TraversalTrace traverseBvh(const BvhImage& image, const QRay& ray);

// ---- A walk set aside and resumed (the treelet schedule, docs/scheduling.md) ----
// The walk's state between two treelet visits: the node it is about to enter
// (its box test passed, not culled), the nodes still to try, and what it has
// done so far (its trace: visits, tests, closest hit). A walk suspended where
// it would enter an interior node of another block and resumed there takes
// exactly the unbroken walk's steps, in any interleaving with other rays.
struct BvhWalkEntry {
  BvhRef ref;
  u128 entry = 0;
  bool operator==(const BvhWalkEntry&) const = default;
};
struct BvhWalk {
  std::optional<BvhWalkEntry> next;  // none: the walk is over
  std::vector<BvhWalkEntry> stack;
  TraversalTrace trace;
  bool done() const { return !next.has_value(); }
  // The treelet block the walk waits for: its next node's (the treelet layout, !done()).
  uint32_t waitsFor(const BvhImage& image) const { return next->ref.leaf ? 0 : image.blockOf(next->ref.first); }
};
BvhWalk startBvhWalk(const BvhImage& image);
// Walks on until the walk ends or is about to enter an interior node of
// another block than the one it is in (`block` at the start) with at most
// kBvhSuspendEntries entries on its stack (without the treelet layout: to the
// end). With more entries it goes on into that block, as the unit does.
void continueBvhWalk(const BvhImage& image, const QRay& ray, BvhWalk& walk, uint32_t block);

// A suspended walk as bvh_walk_t carries it (the unit's res_walk_o and
// ray_walk_i): the closest hit so far (trace.hit; its ray id is not carried),
// the next node, the stack (at most kBvhSuspendEntries entries). The visits
// and counts are the trace's, not the record's.
std::array<u128, valueCount(kBvhWalkFields)> bvhWalkValues(const BvhWalk& walk);
// The record's walk: its next node, stack and closest hit (for ray `rayId`).
BvhWalk bvhWalkOf(std::span<const u128> values, uint32_t rayId);

}  // namespace lancer::fx
