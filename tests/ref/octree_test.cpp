#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "ref/brute_force.h"
#include "ref/octree.h"
#include "scene/scene.h"
#include "support/structure_test_support.h"
#include "structure_tests.h"
#include "support/test_paths.h"

namespace lancer {
namespace {
using namespace test;  // helpers from structure_test_support.h

// ---- Octree-specific helpers.

AccelOptions octreeOptions(int maxDepth, int leafSize = 0) {
  AccelOptions o;
  o.octreeMaxDepth = maxDepth;
  o.octreeLeafSize = leafSize;
  return o;
}

// The split planes of the first `levels` levels along one axis, computed as the
// octree computes them (0.5f * (lo + hi), recursively), plus the box's faces.
void splitPlanes(float lo, float hi, int levels, std::vector<float>& out) {
  if (levels == 0) return;
  const float mid = 0.5f * (lo + hi);
  out.push_back(mid);
  splitPlanes(lo, mid, levels - 1, out);
  splitPlanes(mid, hi, levels - 1, out);
}
std::vector<float> planes(const Octree& tree, int axis, int levels) {
  std::vector<float> out{tree.bounds().lo[axis], tree.bounds().hi[axis]};
  splitPlanes(tree.bounds().lo[axis], tree.bounds().hi[axis], levels, out);
  std::sort(out.begin(), out.end());
  return out;
}

// ---- The tests every structure passes (structure_tests.h), over the octree.

struct OctreeTraits {
  using Accel = Octree;
  static constexpr std::string_view kName = "octree";
  static constexpr StructureSeeds kSeeds{.cornell = 101, .bunny = 102, .wuson = 103, .axisParallel = 104,
                                         .vertices = 105, .octants = 106, .tMax = 110, .faces = 116,
                                         .missing = 117, .intersectP = 118, .flat = 119, .statistics = 120};
  static constexpr size_t kAxisParallelHitDivisor = 8;
  static AccelOptions axisParallelOptions(const Scene&) { return octreeOptions(6, 2); }
  static AccelOptions cornerOptions() { return octreeOptions(4, 1); }
  static AccelOptions facesOptions() { return {}; }
  static AccelOptions flatOptions() { return octreeOptions(6, 2); }
  // The split planes of the first three levels and the box's faces.
  static std::vector<float> crossPlanes(const Octree& tree, int a) { return planes(tree, a, 3); }
  static float midPlane(const Octree& tree, int a) { return planes(tree, a, 1)[1]; }  // the root's
  // The corners of the depth-2 nodes in x and y, of the depth-1 nodes in z.
  static std::array<std::vector<float>, 3> cornerPlanes(const Octree& tree) {
    return {planes(tree, 0, 2), planes(tree, 1, 2), planes(tree, 2, 1)};
  }
  static glm::vec3 cornerStep(const Octree& tree) { return tree.bounds().diagonal() / 4.0f; }  // a depth-2 node
  static void expectBuilt(const Octree& tree) { EXPECT_GT(tree.depth(), 1); }
  static void expectFlat(const Octree&) {}
  static void expectEmpty(const Octree& tree) { EXPECT_EQ(tree.nodeCount(), 0u); }
};

INSTANTIATE_TYPED_TEST_SUITE_P(Octree, Structure, OctreeTraits, StructureName);

// ---- The octree's own tests.

TEST(Octree, SceneFarFromTheOriginMirrorsAboutItsOwnCentre) {
  // Mirroring with o' = -o instead of lo + hi - o is only right for a box centred
  // on the origin; these boxes are nowhere near it, and every octant is used.
  for (const Scene& moved : {translated(bunny(), {1000.0f, -500.0f, 250.0f}),
                             translated(cornell(), {1000.0f, -500.0f, 250.0f})}) {
    const Octree tree(moved, {});
    RayMaker maker(107);
    std::vector<Ray> rays = maker.random(moved, 4000);
    for (size_t i = 0; i < rays.size(); ++i) {
      for (int a = 0; a < 3; ++a)
        rays[i].dir[a] = ((i >> a) & 1 ? -1.0f : 1.0f) * std::abs(rays[i].dir[a]);
    }
    EXPECT_GT(expectSameHits(tree, moved, rays), 400u) << moved.name;
    EXPECT_GT(expectSameHits(tree, moved, verticesAndMidpoints(moved, 300, 108)), 150u)
        << moved.name;
  }
}

TEST(Octree, NonCubicBounds) {
  Scene stretched = cornell();
  for (Triangle& t : stretched.triangles) {
    for (glm::vec3* v : {&t.v0, &t.v1, &t.v2}) *v *= glm::vec3(4.0f, 1.0f, 0.25f);
  }
  stretched.computeBounds();
  const Octree tree(stretched, octreeOptions(5, 2));
  const glm::vec3 size = tree.bounds().diagonal();
  EXPECT_GT(size.x, 10.0f * size.z);
  EXPECT_GT(expectSameHits(tree, stretched, RayMaker(109).random(stretched, 4000)), 1500u);
}

TEST(Octree, DepthOneAndMaxDepth) {
  const Octree shallow(bunny(), octreeOptions(1));
  EXPECT_EQ(shallow.maxDepth(), 1);
  EXPECT_EQ(shallow.depth(), 1);
  EXPECT_EQ(shallow.nodeCount(), 9u);
  EXPECT_GT(expectSameHits(shallow, bunny(), RayMaker(111).random(bunny(), 1500)), 600u);

  const Octree deep(bunny(), octreeOptions(kMaxOctreeDepth, 1));
  EXPECT_EQ(deep.maxDepth(), kMaxOctreeDepth);
  EXPECT_EQ(deep.leafSize(), 1);
  EXPECT_LE(deep.depth(), kMaxOctreeDepth);
  EXPECT_GT(deep.depth(), 6);
  EXPECT_GT(expectSameHits(deep, bunny(), RayMaker(112).random(bunny(), 3000)), 1200u);
  EXPECT_GT(expectSameHits(deep, bunny(), verticesAndMidpoints(bunny(), 300, 113)), 1500u);
}

TEST(Octree, DeepSparseTree) {
  // Two specks pin a unit box; a row of tiny triangles 2^-13 apart near one point
  // forces leaves of size 1 down to depth ~14 along a single path, with almost
  // every other node an empty leaf.
  std::vector<Triangle> tris{{{0, 0, 0}, {1e-3f, 0, 0}, {0, 1e-3f, 0}},
                             {{1, 1, 1}, {1 - 1e-3f, 1, 1}, {1, 1 - 1e-3f, 1}}};
  const float gap = std::ldexp(1.0f, -13);
  for (int i = 0; i < 12; ++i) {
    const glm::vec3 p(0.3f + gap * float(i), 0.3f, 0.3f);
    tris.push_back({p, p + glm::vec3(0, 1e-5f, 0), p + glm::vec3(0, 0, 1e-5f)});
  }
  const Scene scene = fromTriangles(tris);
  const Octree tree(scene, octreeOptions(kMaxOctreeDepth, 1));
  EXPECT_GE(tree.depth(), 12);
  EXPECT_LT(tree.nodeCount(), 8u * 16u * 12u);  // sparse: a few paths, not 8^depth
  // Rays at the tiny triangles (and their vertices), along x through the row,
  // and at random.
  RayMaker maker(114);
  std::vector<Ray> rays = verticesAndMidpoints(scene, 100, 115);
  for (int i = 0; i < 2000; ++i) {
    const Triangle& t = scene.triangles[2 + maker.index(12)];
    Ray r;
    r.origin = maker.inBox(grow(scene.bounds, 0.5f));
    r.dir = maker.pointOn(t) - r.origin;
    rays.push_back(r);
  }
  const float inRow = 0.3f + 2e-6f;
  addAxisParallel(rays, {0.0f, inRow, inRow}, 0);
  addAxisParallel(rays, {0.3f + gap * 5.0f, inRow, 0.0f}, 2);
  EXPECT_GT(expectSameHits(tree, scene, rays), 1500u);
}

TEST(Octree, CloserTriangleInTheNextLeafWins) {
  // Bounds pinned to [0,8]^3 by two specks; leaves of one triangle, depth <= 3
  // (unit leaves). The ray runs along +x from x = 0.5. Triangle 0 is a long
  // slanted sliver listed in the first leaf but hit at x = 4.5; triangle 1 is a
  // small wall at x = 2.5 in a later leaf. Stopping at the first hit found would
  // return triangle 0; the right answer is triangle 1 at t = 2.
  const Scene scene = closerTriangleScene(8.0f);
  const Octree tree(scene, octreeOptions(3, 1));
  // Root, [0,4]^3, leaf [0,2]^3, [2,4]x[0,2]^2, leaf [2,3]x[0,1]^2: then it stops.
  expectCloserTriangleInALaterCellWins(tree, scene, 5);
}

TEST(Octree, TrianglesOnSplitPlanes) {
  const Scene pinned = fromTriangles(pins());
  const Octree lattice(pinned, octreeOptions(1, 1));
  std::array<std::vector<float>, 3> split;
  for (int a = 0; a < 3; ++a) {
    split[a] = planes(lattice, a, 3);
    split[a] = {split[a].begin() + 1, split[a].end() - 1};  // the faces would grow the box
  }
  const Scene scene = latticeScene(split);
  const Octree tree(scene, octreeOptions(4, 1));
  EXPECT_GE(tree.depth(), 3);
  expectLatticeSceneMatches(tree, lattice, scene, 121);
}

TEST(Octree, VisitsOnlyTheChildrenOnTheRay) {
  // One split: the root and eight empty leaves (the specks sit in two corners).
  const Scene scene = fromTriangles(pins());
  const Octree tree(scene, octreeOptions(1, 1));
  ASSERT_EQ(tree.nodeCount(), 9u);
  const float lowMid = 25.0f, highMid = 75.0f;
  TraversalStats stats;
  // Along +x in the upper-y, lower-z quarter: the root and two children. The
  // entry plane is x; the first child must come from comparing tym and tzm with
  // tx0 (child 2), not child 0.
  EXPECT_FALSE(tree.intersect(Ray{{-10.0f, highMid, lowMid}, {1, 0, 0}}, &stats).has_value());
  EXPECT_EQ(stats.nodesVisited, 3u);
  // Mirrored: along -x from the other side, same two children.
  stats = {};
  tree.intersect(Ray{{110.0f, highMid, lowMid}, {-1, -0.0f, 0}}, &stats);
  EXPECT_EQ(stats.nodesVisited, 3u);
  // Entering through the y face into the upper-x, upper-z quarter, leaving
  // through x: children 5 and 7 then out, or 5, 7 (and no others).
  stats = {};
  tree.intersect(Ray{{highMid, -10.0f, highMid}, {0.1f, 1.0f, 0.0f}}, &stats);
  EXPECT_EQ(stats.nodesVisited, 3u);
  // tMax inside the first child: the root and one child.
  stats = {};
  tree.intersect(Ray{{-10.0f, highMid, lowMid}, {1, 0, 0}, 20.0f}, &stats);
  EXPECT_EQ(stats.nodesVisited, 2u);
  // A ray that crosses the y mid-plane before it enters the box through an x
  // face starts in child 2; child 0 (whose interval ends before the entry) is not
  // visited. Path: child 2, then 6 across the x mid-plane, out through y = max.
  stats = {};
  tree.intersect(Ray{{-20.0f, 45.0f, lowMid}, {1.0f, 0.5f, 0.01f}}, &stats);
  EXPECT_EQ(stats.nodesVisited, 3u);
  // tMax before the box: nothing is entered.
  stats = {};
  tree.intersect(Ray{{-10.0f, highMid, lowMid}, {1, 0, 0}, 5.0f}, &stats);
  EXPECT_EQ(stats.nodesVisited, 0u);
  // An origin inside the last child: children behind the origin are not entered.
  stats = {};
  tree.intersect(Ray{{highMid, highMid, lowMid}, {1, 0, 0}}, &stats);
  EXPECT_EQ(stats.nodesVisited, 2u);
}

TEST(Octree, DefaultsAndInvalidOptions) {
  const Octree tree(cornell(), {});
  EXPECT_EQ(tree.maxDepth(), Octree::kDefaultMaxDepth);
  EXPECT_EQ(tree.leafSize(), Octree::kDefaultLeafSize);
  EXPECT_GT(tree.nodeCount(), 1u);
  for (int depth : {-1, kMaxOctreeDepth + 1, 100}) {
    EXPECT_THROW(Octree(cornell(), octreeOptions(depth)), InputError) << depth;
  }
  EXPECT_THROW(Octree(cornell(), octreeOptions(0, -1)), InputError);
  expectInputErrorMentioning([] { Octree(cornell(), octreeOptions(17)); }, {"17", "1..16"});
  EXPECT_NO_THROW(Octree(cornell(), octreeOptions(kMaxOctreeDepth, 1)));
}

}  // namespace
}  // namespace lancer
