// Mixed primitives in the traversal units' golden walks (issue #40,
// docs/quadrics.md, "In the traversal units"): each unit's image lists
// triangles and quadrics in one index list (an entry's kind bit), and its walk
// finds, for every ray, exactly the closest hit of all the image's primitives,
// as a test of every one would; each quadric's lattice bounds hold every hit
// the pipeline computes on it, so the structures list it wherever it may hit.

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/accel_options.h"
#include "driver/chip.h"
#include "golden/primitives.h"
#include "golden/units.h"
#include "support/mixed_scenes.h"

namespace lancer {
namespace {

using test::quantizedMixedScene;

// The closest hit of every primitive of the tables (closerResult), and the
// quadric tests a walk of them all would count.
std::optional<fx::IsectResult> closestOfAll(const fx::PrimitiveTables& tables, const fx::QRay& ray) {
  fx::TraversalTrace all;
  for (const uint32_t entry : tables.entries()) fx::testEntry(all, ray, tables, entry);
  return all.hit;
}

TEST(GoldenMixedWalk, EveryUnitFindsTheClosestOfAllPrimitives) {
  const test::QuantizedMixedScene c = quantizedMixedScene(40, 80, 4000, 4041);
  fx::forEachTraversalUnit([&](auto unit) {
    using U = decltype(unit);
    const typename U::Image image = U::build(c.triangles, AccelOptions{}, c.quadrics);
    const fx::PrimitiveTables tables = fx::tablesOf(image);
    ASSERT_EQ(tables.triangles.size(), c.triangles.size()) << U::kNames.unit;
    ASSERT_EQ(tables.quadrics.size(), c.quadrics.size()) << U::kNames.unit;
    uint64_t tests = 0, quadricTests = 0, quadricHits = 0, hits = 0;
    for (const fx::QRay& ray : c.rays) {
      const fx::TraversalTrace trace = U::traverse(image, ray);
      const std::optional<fx::IsectResult> expected = closestOfAll(tables, ray);
      ASSERT_EQ(trace.hit, expected) << U::kNames.unit << ": ray " << ray.id;
      EXPECT_LE(trace.quadricTests, trace.tests) << U::kNames.unit << ": ray " << ray.id;
      tests += trace.tests;
      quadricTests += trace.quadricTests;
      if (expected) {
        ++hits;
        if (expected->primId >= c.triangles.size()) ++quadricHits;
      }
    }
    // The structure culls (fewer tests than all primitives for every ray) and
    // its walks meet both kinds.
    EXPECT_LT(tests, c.rays.size() * tables.size() / 2) << U::kNames.unit;
    EXPECT_GT(quadricTests, 0u) << U::kNames.unit;
    EXPECT_LT(quadricTests, tests) << U::kNames.unit;
    EXPECT_GT(quadricHits, c.rays.size() / 10) << U::kNames.unit;
    EXPECT_GT(hits - quadricHits, c.rays.size() / 20) << U::kNames.unit;
  });
}

// A lattice box closed on both sides; a point within `slack` of it.
bool holds(const fx::LatticeBox& box, const std::array<double, 3>& p, double slack) {
  for (size_t a = 0; a < 3; ++a) {
    if (p[a] < double(box.lo[a]) - slack || p[a] > double(box.hi[a]) + slack) return false;
  }
  return true;
}

TEST(GoldenMixedWalk, QuadricBoundsHoldEveryComputedHit) {
  const test::QuantizedMixedScene c = quantizedMixedScene(0, 200, 20000, 4042);
  uint64_t hits = 0, rounded = 0;
  for (const fx::QQuadric& q : c.quadrics) rounded += q.scaleExp > 0;
  EXPECT_GT(rounded, 0u);  // cones whose records are rounded are among them
  for (const fx::QRay& ray : c.rays) {
    for (const fx::QQuadric& q : c.quadrics) {
      const fx::IsectResult r = fx::intersectQuadric(ray, q);
      if (!r.hit) continue;
      ++hits;
      // t_num / det is the displacement along the dominant axis, in lattice units.
      const double along = double(r.tNum) / double(r.det);
      const double dz = std::abs(double(ray.dir[size_t(fx::dominantAxis(ray.dir))]));
      std::array<double, 3> p{};
      for (size_t a = 0; a < 3; ++a) p[a] = double(ray.org[a]) + double(ray.dir[a]) * along / dz;
      ASSERT_TRUE(holds(q.bounds, p, 1e-6)) << "ray " << ray.id << ", quadric " << q.id << " at (" << p[0] << ", "
                                            << p[1] << ", " << p[2] << ")";
    }
  }
  EXPECT_GT(hits, 1000u);
}

// The treelet layout puts each kind's table in leaf order: the walks keep
// their hits (records carry their ids), their visits and tests.
TEST(GoldenMixedWalk, BvhTreeletLayoutKeepsEveryWalk) {
  const test::QuantizedMixedScene c = quantizedMixedScene(60, 60, 1500, 4043);
  const fx::BvhImage plain = fx::buildBvhImage(c.triangles, fx::kDefaultBvhLeafSize, c.quadrics);
  fx::BvhImage blocked = plain;
  fx::layoutBvhTreelets(blocked, 4);
  for (const fx::QRay& ray : c.rays) {
    const fx::TraversalTrace a = fx::traverseBvh(plain, ray), b = fx::traverseBvh(blocked, ray);
    ASSERT_EQ(a.hit, b.hit) << "ray " << ray.id;
    ASSERT_EQ(a.tests, b.tests) << "ray " << ray.id;
    ASSERT_EQ(a.quadricTests, b.quadricTests) << "ray " << ray.id;
  }
  // Each kind's entries count 0, 1, 2, ... along the list.
  uint32_t triangles = 0, quadrics = 0;
  for (const uint32_t entry : blocked.indices) {
    EXPECT_EQ(fx::entryPlace(entry), fx::isQuadricEntry(entry) ? quadrics++ : triangles++);
  }
  EXPECT_EQ(triangles, c.triangles.size());
  EXPECT_EQ(quadrics, c.quadrics.size());
}

// Each cell's and leaf's list is ascending: its triangles, then its quadrics.
TEST(GoldenMixedWalk, ListsHoldTrianglesThenQuadrics) {
  const test::QuantizedMixedScene c = quantizedMixedScene(30, 30, 0, 4044);
  const fx::GridImage grid = fx::buildGridImage(c.triangles, {8, 8, 8}, c.quadrics);
  for (const fx::GridCell& cell : grid.cells) {
    const auto first = grid.indices.begin() + cell.first;
    EXPECT_TRUE(std::is_sorted(first, first + cell.count));
  }
  EXPECT_TRUE(std::any_of(grid.indices.begin(), grid.indices.end(), fx::isQuadricEntry));
  const fx::OctreeImage octree = fx::buildOctreeImage(c.triangles, 6, 4, c.quadrics);
  for (const fx::OctreeNode& node : octree.nodes) {
    if (!node.leaf) continue;
    const auto first = octree.indices.begin() + node.first;
    EXPECT_TRUE(std::is_sorted(first, first + node.count));
  }
}

// The image's size counts the quadric table (68 bytes a record at 16/16),
// which the triangle port reads at an entry with the kind bit.
TEST(GoldenMixedWalk, AddressMapPlacesTheQuadricTable) {
  const test::QuantizedMixedScene c = quantizedMixedScene(10, 10, 0, 4045);
  const fx::GridImage image = fx::GridUnit::build(c.triangles, AccelOptions{}, c.quadrics);
  const mem::AddressMap map = addressMapOf<fx::GridUnit>(image);
  const mem::Region& quadrics = map.quadricRegion();
  EXPECT_EQ(quadrics.records, c.quadrics.size());
  EXPECT_EQ(quadrics.recordBytes, uint32_t((fx::kIsectQuadricBits + 7) / 8));
  const mem::ReadSpan second = map.span(mem::Port::Triangle, fx::quadricEntry(1));
  EXPECT_EQ(second.first, quadrics.base + quadrics.recordBytes);
  EXPECT_EQ(second.bytes, quadrics.recordBytes);
  EXPECT_EQ(map.span(mem::Port::Triangle, 1).first,
            map.region(mem::Port::Triangle).base + map.region(mem::Port::Triangle).recordBytes);
  EXPECT_EQ(map.maxReadBytes(mem::Port::Triangle), std::max(quadrics.recordBytes, map.region(mem::Port::Triangle).recordBytes));
  EXPECT_GE(map.end(), quadrics.base + quadrics.bytes());
}

}  // namespace
}  // namespace lancer
