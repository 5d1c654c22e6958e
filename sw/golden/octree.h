#pragma once

// Bit-accurate model of the fixed-point octree stepping unit (rt_octree): the
// memory image the driver builds, and the parametric traversal of Revelles,
// Urena and Lastra (2000) in exact integers that defines which nodes each ray
// visits and which hit it returns. docs/octree-unit.md has the derivation.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "golden/lattice.h"
#include "golden/octree_formats.h"
#include "golden/primitives.h"
#include "golden/records.h"
#include "golden/trace.h"

namespace lancer::fx {

// One node: an interior node's eight children are consecutive, child i at
// first + i, where i = 4x + 2y + z names the upper half on each axis; a leaf
// names a run of the index list.
struct OctreeNode {
  bool leaf = true;
  uint32_t first = 0;  // interior: index of child 0; leaf: first index-list entry
  uint32_t count = 0;  // leaf: primitives listed; interior: 0
  bool operator==(const OctreeNode&) const = default;
};

struct OctreeImage {
  int maxDepth = 0;
  int leafSize = 0;
  std::vector<OctreeNode> nodes;     // node 0 is the root
  std::vector<uint32_t> indices;     // primitive entries (golden/primitives.h); ascending within a leaf
  std::vector<QTriangle> triangles;  // by place (a triangle's place is its id)
  std::vector<QQuadric> quadrics;    // by place
  int depth = 0;                     // deepest leaf built
  // The treelet layout (layoutOctreeTreelets); 0 treeletNodes: the depth-first layout.
  uint32_t treeletNodes = 0;         // node-table entries of a treelet block (a power of two, >= 8)
  size_t treelets = 0;               // connected subtrees of child groups, packed into the blocks
  size_t paddingNodes = 0;           // entries never read (block ends, the root's group slot)
  // The treelet block of node-table entry `index` (one block without the layout).
  uint32_t blockOf(uint32_t index) const { return treeletNodes ? index / treeletNodes : 0; }
};

inline constexpr int kDefaultOctreeLeafSize = 8;
// Deep enough that leaves hold about kDefaultOctreeLeafSize triangles on
// typical meshes; never deeper than the formats allow.
int defaultOctreeDepth(size_t triangles);

// Builds top-down over the lattice cube: a node becomes a leaf at maxDepth,
// when it holds at most leafSize primitives, or when splitting would not lower
// the expected tests of a ray crossing it (the children's counts, summed, at
// least four times the node's: each child has a quarter of its surface).
// Primitives are binned by their lattice boxes (a triangle's integer bounding
// box, a quadric's record bounds) against closed child boxes, so a primitive
// on a split plane is listed on both sides. Throws InputError for a depth outside 1..kOctreeMaxDepth,
// a leaf size < 1, or an image that does not fit kMemAddrBits.
OctreeImage buildOctreeImage(std::vector<QTriangle> triangles, int maxDepth, int leafSize,
                             std::vector<QQuadric> quadrics = {});

// One plane parameter over the common denominator, or +-infinity for an axis
// the ray never crosses.
struct OctT {
  i128 value = 0;
  int8_t inf = 0;  // -1: -inf, +1: +inf, 0: finite `value`
  bool operator<(const OctT& o) const {
    if (inf != o.inf) return inf < o.inf;
    return inf == 0 && value < o.value;
  }
  bool operator==(const OctT& o) const = default;
};

using OctreeTrace = TraversalTrace;

// The per-ray setup of the unit: the mirrored ray (origin o' = min + max - o,
// i.e. 2^P - o, for a negative component; `mirror` gets 4/2/1 for x/y/z) and
// the root's six plane parameters. Multiplications only.
struct OctreeRaySetup : MirroredRay {
  std::array<OctT, 3> t0{}, t1{};  // root plane parameters per axis
  static OctreeRaySetup setup(const QRay& ray);
};

// The first child a ray enters, from the entry plane (the largest t0) and the
// mid-plane parameters (Revelles' table 1).
int firstChild(const std::array<OctT, 3>& t0, const std::array<OctT, 3>& tm);
// The child after `child` (0..7, in mirrored numbering) given its exit
// parameters; 8 means the ray leaves the parent (Revelles' table 2). Exact
// ties go to the later axis, as in the paper.
int nextChild(int child, const std::array<OctT, 3>& childT1);

// True if `hit` lies within a node whose exit parameters are `t1`:
// t_hit <= min(t1), exactly.
bool hitWithin(const IsectResult& hit, const std::array<OctT, 3>& t1, const OctreeRaySetup& ray);

// The reference behaviour of the unit for one ray.
OctreeTrace traverseOctree(const OctreeImage& image, const QRay& ray);

// The treelet layout (docs/scheduling.md, "The treelet layout"): the tree of
// child groups cut greedily into treelets of at most `blockNodes / 8` groups
// (Aila & Karras 2010: from a treelet's root group, the frontier group with
// the largest surface area joins, i.e. the shallowest, then the lowest index,
// until the treelet is full; the groups left over root new treelets), packed
// next-fit into aligned blocks of `blockNodes` node-table entries. The root
// keeps entry 0 (its record is a configuration input, never read), entries
// 1..7 are padding, and every group starts at a multiple of 8, so a group
// never straddles two blocks. The index list is laid out in node-table order
// and the primitives renumbered by their first listing (ascending within a
// leaf still). Every ray walks the same nodes to the same hit, under new
// numbers. Throws InputError unless `blockNodes` is a power of two >= 8.
void layoutOctreeTreelets(OctreeImage& image, uint32_t blockNodes);

// ---- A walk set aside and resumed (the treelet schedule, docs/scheduling.md) ----
// The walk as rt_octree steps it (traverseOctree is this walk unbroken): the
// node's plane parameters and the stack of {group base, child} per level (no
// parameters on the stack: halvings are exact, so a child's give back its
// parent's), between its reads of child groups. A walk suspended before a
// descent and resumed later makes exactly the unbroken walk's steps, in any
// interleaving with other rays.
struct OctreeLevel {
  uint32_t first = 0;  // the level's child-group base
  uint8_t child = 0;   // which of its children the walk is in (mirrored numbering)
  bool operator==(const OctreeLevel&) const = default;
};
struct OctreeWalk {
  enum class Next : uint8_t {
    Start,    // a fresh ray: the root test, then the root
    Descend,  // read `group` (the entered node's children), then descend into the first child
    Refill,   // read `group` (the stack top's), then enter the stack top's child (never suspended)
    Over,
  };
  Next next = Next::Start;
  uint32_t group = 0;
  std::array<OctT, 3> t0{}, t1{};   // the node entered (Descend) or to enter (Refill)
  std::vector<OctreeLevel> stack;   // levels 0 .. depth - 1
  OctreeTrace trace;                // visits, tests and closest hit so far
  bool done() const { return next == Next::Over; }
  // The treelet block the walk waits for: its next group read's (the treelet layout).
  uint32_t waitsFor(const OctreeImage& image) const { return image.blockOf(group); }
};
// A fresh walk, in the block of the root's child group (0 for a leaf root).
OctreeWalk startOctreeWalk(const OctreeImage& image);
// Walks on until the walk ends or is about to descend into a node whose child
// group lies in another treelet block than `block`, with at most
// kOctreeSuspendLevels levels on its stack (without the treelet layout: to
// the end).
void continueOctreeWalk(const OctreeImage& image, const QRay& ray, OctreeWalk& walk, uint32_t block);

// A suspended walk as octree_walk_t carries it: the closest hit so far, the
// group it reads first, the node's parameters, the stack. The visits and test counts
// so far stay with the ray (the run joins them).
std::array<u128, valueCount(kOctreeWalkFields)> octreeWalkValues(const OctreeWalk& walk);
// The record's walk for `ray` (its setup gives back the infinities of the axes
// it never crosses; its id names the closest hit).
OctreeWalk octreeWalkOf(std::span<const u128> values, const QRay& ray);
// The octree's walk state when it is suspended, as a ray queue holds it: the
// ray record and its octree_walk_t with `levels` stack levels (the record's
// unused levels are not stored).
constexpr int octreeSuspendedBits(size_t levels) {
  return kIsectRayBits + kOctreeWalkBits -
         (32 + kOctreeChildBits) * (kOctreeSuspendLevels - int(levels));
}
// The crossings of `ray`'s walk over a treelet layout (none without one).
TreeletCrossings octreeTreeletCrossings(const OctreeImage& image, const QRay& ray);

}  // namespace lancer::fx
