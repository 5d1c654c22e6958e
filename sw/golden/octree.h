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

}  // namespace lancer::fx
