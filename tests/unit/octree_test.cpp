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
#include "structure_test_support.h"
#include "test_paths.h"

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

// ---- Tests.

TEST(Octree, MatchesBruteForceOnCornellBox) {
  const Octree tree(cornell(), {});
  EXPECT_EQ(tree.name(), "octree");
  EXPECT_GT(tree.depth(), 1);
  const size_t hits = expectSameHits(tree, cornell(), RayMaker(101).random(cornell(), 20000));
  EXPECT_GT(hits, 8000u);
}

TEST(Octree, MatchesBruteForceOnBunny) {
  const Octree tree(bunny(), {});
  const size_t hits = expectSameHits(tree, bunny(), RayMaker(102).random(bunny(), 5000));
  EXPECT_GT(hits, 2000u);
}

TEST(Octree, MatchesBruteForceOnWuson) {
  const Octree tree(wuson(), {});
  const size_t hits = expectSameHits(tree, wuson(), RayMaker(103).random(wuson(), 5000));
  EXPECT_GT(hits, 2000u);
}

TEST(Octree, AxisParallelRaysInMidPlanes) {
  // Origins where the split planes of the first three levels (and the box's
  // faces) cross: rays lying in one or two mid-planes, with +0 and -0 zero
  // components, from outside the box and from inside it.
  for (const Scene* scene : {&cornell(), &bunny()}) {
    const Octree tree(*scene, octreeOptions(6, 2));
    std::vector<Ray> rays;
    for (int axis = 0; axis < 3; ++axis) {
      const int p = (axis + 1) % 3, q = (axis + 2) % 3;
      const std::vector<float> inside = planes(tree, axis, 1);
      for (float x : planes(tree, p, 3)) {
        for (float y : planes(tree, q, 3)) {
          glm::vec3 o;
          o[p] = x;
          o[q] = y;
          o[axis] = tree.bounds().lo[axis] - 0.25f * tree.bounds().diagonal()[axis];
          addAxisParallel(rays, o, axis);
          o[axis] = inside[1];  // on the root's mid-plane
          addAxisParallel(rays, o, axis);
        }
      }
    }
    RayMaker maker(104);
    for (int i = 0; i < 250; ++i) {
      glm::vec3 o = maker.inBox(scene->bounds);
      const int axis = i % 3;
      o[(axis + 1) % 3] =
          i % 2 ? scene->bounds.lo[(axis + 1) % 3] : scene->bounds.hi[(axis + 1) % 3];
      addAxisParallel(rays, o, axis);
    }
    EXPECT_GT(expectSameHits(tree, *scene, rays), rays.size() / 8) << scene->name;
  }
}

TEST(Octree, RaysThroughNodeEdgesAndCorners) {
  const Octree tree(cornell(), octreeOptions(4, 1));
  const glm::vec3 node = tree.bounds().diagonal() / 4.0f;  // a depth-2 node
  std::vector<Ray> rays;
  for (float x : planes(tree, 0, 2)) {
    for (float y : planes(tree, 1, 2)) {
      for (float z : planes(tree, 2, 1)) {
        const glm::vec3 o(x, y, z);
        for (int s = 0; s < 8; ++s) {
          const glm::vec3 sign(s & 4 ? -1 : 1, s & 2 ? -1 : 1, s & 1 ? -1 : 1);
          rays.push_back(Ray{o, sign * node});
          rays.push_back(Ray{o, sign * glm::vec3(node.x, node.y, 0.0f)});
          rays.push_back(Ray{o, sign * glm::vec3(0.0f, node.y, node.z)});
          rays.push_back(Ray{o, sign * glm::vec3(node.x, -0.0f, node.z)});
        }
      }
    }
  }
  EXPECT_GT(expectSameHits(tree, cornell(), rays), rays.size() / 4);
}

TEST(Octree, RaysAtVerticesAndEdgeMidpoints) {
  for (const Scene* scene : {&cornell(), &bunny()}) {
    const Octree tree(*scene, {});
    const auto rays = verticesAndMidpoints(*scene, 600, 105);
    EXPECT_GT(expectSameHits(tree, *scene, rays), rays.size() * 9 / 10) << scene->name;
  }
}

TEST(Octree, AllEightOctants) {
  const Octree tree(bunny(), {});
  RayMaker maker(106);
  for (int octant = 0; octant < 8; ++octant) {
    std::vector<Ray> rays;
    for (const Ray& r : maker.random(bunny(), 600)) {
      Ray m = r;
      for (int a = 0; a < 3; ++a)
        m.dir[a] = ((octant >> a) & 1 ? -1.0f : 1.0f) * std::abs(r.dir[a]);
      rays.push_back(m);
    }
    EXPECT_GT(expectSameHits(tree, bunny(), rays), 30u) << "octant " << octant;
  }
}

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

TEST(Octree, TMaxLimitsHits) {
  const Octree tree(bunny(), {});
  const BruteForce brute(bunny());
  std::vector<Ray> rays;
  size_t shortened = 0;
  for (Ray r : RayMaker(110).random(bunny(), 1500)) {
    r.tMax = kInfinity;
    const auto hit = brute.intersect(r);
    if (!hit) continue;
    // At the hit, one ulp short of it, and half way. The triangle test decides
    // t <= tMax before its final division, so one ulp short may still keep the
    // hit (BruteForce agrees, which expectSameHits checks); half way may not.
    for (float tMax : {hit->t, std::nextafter(hit->t, 0.0f), 0.5f * hit->t}) {
      r.tMax = tMax;
      rays.push_back(r);
    }
    const auto half = tree.intersect(r);
    if (half) {
      EXPECT_LE(half->t, r.tMax) << describe(r);
      EXPECT_NE(half->prim, hit->prim) << describe(r);
    }
    shortened += !half;
  }
  EXPECT_GT(shortened, 250u);
  expectSameHits(tree, bunny(), rays);
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

TEST(Octree, OriginsOnBoundsFaces) {
  for (const Scene* scene : {&cornell(), &bunny()}) {
    const Octree tree(*scene, {});
    RayMaker maker(116);
    std::vector<Ray> rays;
    for (const Aabb& box : {scene->bounds, tree.bounds()}) {
      for (int i = 0; i < 1200; ++i) {
        Ray r;
        r.origin = maker.inBox(box);
        r.origin[i % 3] = (i / 3) % 2 ? box.hi[i % 3] : box.lo[i % 3];
        r.dir = i % 4 ? maker.direction()
                      : maker.pointOn(scene->triangles[maker.index(scene->size())]) - r.origin;
        rays.push_back(r);
      }
    }
    EXPECT_GT(expectSameHits(tree, *scene, rays), rays.size() / 5) << scene->name;
  }
}

TEST(Octree, RaysMissingTheScene) {
  const Octree tree(bunny(), {});
  const Aabb b = bunny().bounds;
  const glm::vec3 size = b.diagonal();
  RayMaker maker(117);
  std::vector<Ray> rays;
  for (int i = 0; i < 2000; ++i) {
    Ray r;
    const int a = i % 3;
    r.origin = maker.inBox(grow(b, 0.5f));
    // Beside the box on axis a, moving parallel to that face or away from it.
    r.origin[a] = b.hi[a] + maker.uniform(0.01f, 1.0f) * size[a];
    r.dir = maker.direction();
    r.dir[a] = i % 2 ? std::abs(r.dir[a]) : (i % 4 ? 0.0f : -0.0f);
    rays.push_back(r);
  }
  for (int i = 0; i < 500; ++i) {
    Ray r;
    r.origin = b.lo - size * maker.uniform(0.01f, 1.0f);
    r.dir = -glm::abs(maker.direction());
    rays.push_back(r);
  }
  EXPECT_EQ(expectSameHits(tree, bunny(), rays), 0u);
  TraversalStats stats;
  for (const Ray& r : rays) EXPECT_FALSE(tree.intersect(r, &stats).has_value());
  EXPECT_EQ(stats.triangleTests, 0u);  // rejected at the root box
}

TEST(Octree, IntersectPAgreesWithIntersect) {
  const Octree tree(wuson(), {});
  size_t hits = 0;
  for (const Ray& r : RayMaker(118).random(wuson(), 4000)) {
    const bool any = tree.intersectP(r);
    EXPECT_EQ(any, tree.intersect(r).has_value()) << describe(r);
    hits += any;
  }
  EXPECT_GT(hits, 1500u);
}

TEST(Octree, CloserTriangleInTheNextLeafWins) {
  // Bounds pinned to [0,8]^3 by two specks; leaves of one triangle, depth <= 3
  // (unit leaves). The ray runs along +x from x = 0.5. Triangle 0 is a long
  // slanted sliver listed in the first leaf but hit at x = 4.5; triangle 1 is a
  // small wall at x = 2.5 in a later leaf. Stopping at the first hit found would
  // return triangle 0; the right answer is triangle 1 at t = 2.
  const Scene scene = fromTriangles({
      {{1.0f, 0.0f, 0.0f}, {8.0f, 1.0f, 0.0f}, {4.5f, 0.5f, 4.0f}},
      {{2.5f, 0.3f, 0.3f}, {2.5f, 0.7f, 0.4f}, {2.5f, 0.4f, 0.7f}},
      {{0.0f, 7.0f, 7.0f}, {0.0f, 7.0f, 7.1f}, {0.0f, 7.1f, 7.0f}},
      {{8.0f, 8.0f, 8.0f}, {8.0f, 7.9f, 8.0f}, {8.0f, 8.0f, 7.9f}},
  });
  const Octree tree(scene, octreeOptions(3, 1));
  const Ray ray{{0.5f, 0.5f, 0.5f}, {1.0f, 0.0f, 0.0f}};
  TraversalStats stats;
  const auto hit = tree.intersect(ray, &stats);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->prim, 1u);
  EXPECT_EQ(hit->t, 2.0f);
  // Root, [0,4]^3, leaf [0,2]^3, [2,4]x[0,2]^2, leaf [2,3]x[0,1]^2: then it stops.
  EXPECT_LE(stats.nodesVisited, 5u);
  Ray open = ray;
  open.origin.z = 2.0f;  // above the wall, still through the sliver
  const auto far = tree.intersect(open);
  ASSERT_TRUE(far.has_value());
  EXPECT_EQ(far->prim, 0u);
  expectSameHits(tree, scene, {ray, open});
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
  ASSERT_EQ(tree.bounds().lo, lattice.bounds().lo);
  ASSERT_EQ(tree.bounds().hi, lattice.bounds().hi);
  EXPECT_GE(tree.depth(), 3);
  const auto rays = latticeRays(scene, 121);
  EXPECT_GT(expectSameHits(tree, scene, rays), rays.size() * 3 / 4);
}

TEST(Octree, VisitsOnlyTheChildrenOnTheRay) {
  // One split: the root and eight empty leaves (the specks sit in two corners).
  const Octree tree(fromTriangles(pins()), octreeOptions(1, 1));
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

TEST(Octree, FlatAndEmptyScenes) {
  std::vector<Triangle> tris;
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      const float x = float(i), y = float(j);
      tris.push_back({{x, y, 0}, {x + 1, y, 0}, {x + 1, y + 1, 0}});
      tris.push_back({{x, y, 0}, {x + 1, y + 1, 0}, {x, y + 1, 0}});
    }
  }
  const Scene flat = fromTriangles(tris);
  const Octree tree(flat, octreeOptions(6, 2));
  RayMaker maker(119);
  std::vector<Ray> rays;
  for (int i = 0; i < 3000; ++i) {
    Ray r;
    r.origin = maker.inBox(Aabb{{-5, -5, -5}, {15, 15, 5}});
    r.dir = i % 2 ? maker.pointOn(tris[maker.index(tris.size())]) - r.origin : maker.direction();
    rays.push_back(r);
  }
  for (int i = 0; i <= 10; ++i) {
    addAxisParallel(rays, {float(i), -1.0f, 0.0f}, 1);  // in the plane, along a seam
    addAxisParallel(rays, {float(i), 0.5f, 1.0f}, 2);   // onto an edge
  }
  EXPECT_GT(expectSameHits(tree, flat, rays), 1000u);

  const Scene empty{};
  const Octree none(empty, {});
  EXPECT_EQ(none.nodeCount(), 0u);
  EXPECT_FALSE(none.intersect(Ray{}).has_value());
  EXPECT_FALSE(none.intersectP(Ray{}));
}

TEST(Octree, DegenerateRaysHitNothing) {
  const Octree accel(cornell(), {});
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const glm::vec3 centre = cornell().bounds.center();
  for (const Ray& r :
       {Ray{centre, glm::vec3(0.0f)}, Ray{centre, glm::vec3(-0.0f)}, Ray{centre, {nan, 1, 0}},
        Ray{{nan, 0, 0}, {0, 1, 0}}, Ray{centre, {kInfinity, 1, 0}}, Ray{centre, {0, 1, 0}, nan}}) {
    EXPECT_FALSE(accel.intersect(r).has_value()) << describe(r);
    EXPECT_FALSE(accel.intersectP(r)) << describe(r);
  }
  // A valid ray from the same point does hit (the walls are closed above and below).
  EXPECT_TRUE(accel.intersect(Ray{centre, {0, 1, 0}}).has_value());
}

TEST(Octree, CountsStatistics) {
  const Octree tree(bunny(), {});
  TraversalStats stats;
  size_t hits = 0;
  const auto rays = RayMaker(120).random(bunny(), 200);
  for (const Ray& r : rays) hits += tree.intersect(r, &stats).has_value();
  EXPECT_GT(hits, 50u);
  EXPECT_GT(stats.nodesVisited, rays.size());
  EXPECT_GT(stats.triangleTests, hits);
  EXPECT_LT(stats.triangleTests, rays.size() * bunny().size() / 20);
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
  try {
    Octree(cornell(), octreeOptions(17));
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("17"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1..16"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(Octree(cornell(), octreeOptions(kMaxOctreeDepth, 1)));
}

}  // namespace
}  // namespace lancer
