// The ray segment and the any-hit flag in the golden models of the pipeline
// and of both traversal units: a hit counts iff it lies within the segment
// (a hit exactly at the end counts), a bounded walk stops where its segment
// ends, and an any-hit walk stops after the first region with a hit.
#include <gtest/gtest.h>

#include <optional>

#include "golden/grid.h"
#include "golden/isect.h"
#include "golden/octree.h"
#include "scene/scene.h"
#include "support/traversal_cases.h"

namespace lancer::fx {
namespace {

using test::QuantizedScene;

QRay unbounded(QRay ray) {
  ray.tMax = kSegEndNone;
  ray.anyHit = false;
  return ray;
}

bool isPrefix(const std::vector<uint32_t>& shorter, const std::vector<uint32_t>& longer) {
  return shorter.size() <= longer.size() && std::equal(shorter.begin(), shorter.end(), longer.begin());
}

TEST(GoldenSegment, PipelineCountsAHitExactlyAtTheEnd) {
  const QuantizedScene wall = test::segmentScene(int64_t(1) << (kPosBits - 1), 100);
  // The ray beside the occluder, straight up: the wall is exactly (2^(P-1) - 100) units away.
  QRay ray{7, {kPosMax / 8 + kPosMax / 16, kPosMax / 8 + kPosMax / 16, 100}, {0, 0, kDirMax}};
  const uint64_t toWall = uint64_t((int64_t(1) << (kPosBits - 1)) - 100) << kSegFracBits;
  ray.tMax = toWall;
  const IsectResult at = intersect(ray, wall.triangles[0]);
  ASSERT_TRUE(at.hit);
  EXPECT_TRUE(test::segmentCodeOf(at).exact);
  EXPECT_EQ(test::segmentCodeOf(at).floor, toWall);
  ray.tMax = toWall - 1;
  const IsectResult beyond = intersect(ray, wall.triangles[0]);
  EXPECT_FALSE(beyond.hit);
  EXPECT_EQ(beyond.tNum, 0u) << "a miss outputs zeros";
  ray.tMax = 0;
  EXPECT_FALSE(intersect(ray, wall.triangles[0]).hit);
}

// Every unit's walk over the same rays: bounded closest hits equal brute force
// within the segment, any-hit answers agree on hit/miss and never test more,
// and a bounded walk visits a prefix of the unbounded one.
template <class Walk>
void expectSegmentRules(const char* unit, const std::vector<QTriangle>& tris, const std::vector<QRay>& rays,
                        const Walk& walk) {
  uint64_t anyHitTests = 0, closestTests = 0;
  size_t bounded = 0, anyHits = 0, hits = 0;
  for (const QRay& ray : rays) {
    SCOPED_TRACE(testing::Message() << unit << " " << test::describeLatticeRay(ray));
    const TraversalTrace trace = walk(ray);
    const std::optional<IsectResult> expected = test::bruteForceHit(tris, ray);
    const TraversalTrace full = walk(unbounded(ray));
    EXPECT_TRUE(isPrefix(trace.visits, full.visits)) << "a segment only cuts the walk short";
    EXPECT_LE(trace.tests, full.tests);
    hits += expected.has_value();
    if (ray.anyHit) {
      ++anyHits;
      EXPECT_EQ(trace.hit.has_value(), expected.has_value());
      QRay closest = ray;
      closest.anyHit = false;
      const TraversalTrace closestTrace = walk(closest);
      EXPECT_TRUE(isPrefix(trace.visits, closestTrace.visits));
      anyHitTests += trace.tests;
      closestTests += closestTrace.tests;
    } else {
      bounded += ray.bounded();
      EXPECT_EQ(trace.hit, expected);
    }
  }
  EXPECT_GT(bounded, 20u);
  EXPECT_GT(anyHits, 20u);
  EXPECT_GT(hits, 20u);
  EXPECT_LT(anyHitTests, closestTests) << "any-hit saves tests on these rays";
}

std::vector<QRay> allSegmentRays(const std::vector<QTriangle>& tris, const std::vector<QRay>& wallRays) {
  std::mt19937_64 rng(31);
  std::vector<QRay> seeds;
  for (uint32_t i = 0; i < 80; ++i) seeds.push_back(test::randomLatticeRay(rng, i));
  std::vector<QRay> rays = test::segmentVariants(tris, seeds, seeds.size());
  rays.insert(rays.end(), wallRays.begin(), wallRays.end());
  return rays;
}

class GoldenSegmentWalks : public ::testing::TestWithParam<int64_t> {};  // the wall's z

TEST_P(GoldenSegmentWalks, GridAndOctreeFollowTheSegmentRules) {
  const QuantizedScene wall = test::segmentScene(GetParam(), kPosMax / 16 + 3);
  std::mt19937_64 rng(37);
  std::vector<QTriangle> tris = test::randomLatticeTriangles(rng, 300, 0, kPosMax, kPosMax / 12);
  for (QTriangle t : wall.triangles) {
    t.id = uint32_t(tris.size());
    tris.push_back(t);
  }
  std::vector<QRay> wallRays = wall.rays;
  const std::vector<QRay> rays = allSegmentRays(tris, wallRays);
  const GridImage grid = buildGridImage(tris, {16, 16, 16});
  expectSegmentRules("grid", tris, rays, [&](const QRay& r) { return traverseGrid(grid, r); });
  const OctreeImage octree = buildOctreeImage(tris, std::min(6, kOctreeMaxDepth), 4);
  expectSegmentRules("octree", tris, rays, [&](const QRay& r) { return traverseOctree(octree, r); });
}

INSTANTIATE_TEST_SUITE_P(Walls, GoldenSegmentWalks,
                         ::testing::Values(int64_t(1) << (kPosBits - 1),  // on a cell and node boundary
                                           kPosMax / 3 + 1));             // on none

}  // namespace
}  // namespace lancer::fx
