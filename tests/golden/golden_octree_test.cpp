#include <gtest/gtest.h>

#include <random>

#include "common/error.h"
#include "driver/quantize.h"
#include "golden/isect.h"
#include "golden/memory_image.h"
#include "golden/octree.h"
#include "scene/scene.h"
#include "support/structure_test_support.h"
#include "support/test_paths.h"
#include "support/traversal_cases.h"

namespace lancer::fx {
namespace {
using namespace lancer::test;  // quantizeScene, bruteForceHit, randomLatticeRay (support/traversal_cases.h)

struct Config {
  int depth, leaf;
};

class GoldenOctreeConfigs : public ::testing::TestWithParam<Config> {};

TEST_P(GoldenOctreeConfigs, ClosestHitEqualsBruteForceOnTheBunny) {
  static const std::vector<QTriangle> tris = quantizeScene(loadScene(test::kBunny));
  const Config c{std::min(GetParam().depth, kOctreeMaxDepth), GetParam().leaf};  // narrow formats are shallower
  const OctreeImage image = buildOctreeImage(tris, c.depth, c.leaf);
  std::mt19937_64 rng(uint64_t(c.depth * 100 + c.leaf));
  for (uint32_t i = 0; i < 400; ++i) {
    const QRay ray = randomLatticeRay(rng, i);
    const OctreeTrace trace = traverseOctree(image, ray);
    ASSERT_EQ(trace.hit, bruteForceHit(tris, ray)) << "ray " << i << " depth " << c.depth << " leaf " << c.leaf;
    ASSERT_FALSE(trace.visits.empty());
    EXPECT_EQ(trace.visits.front(), 0u) << "the walk starts at the root";
  }
}
INSTANTIATE_TEST_SUITE_P(DepthsAndLeaves, GoldenOctreeConfigs,
                         ::testing::Values(Config{1, 8}, Config{3, 8}, Config{6, 8}, Config{8, 1}, Config{12, 4},
                                           Config{kOctreeMaxDepth, 1}));

TEST(GoldenOctree, AllEightOctantsAndAxisParallelRays) {
  const auto tris = quantizeScene(makeCornellBox());
  const OctreeImage image = buildOctreeImage(tris, 6, 2);
  const int64_t mid = int64_t(1) << (kPosBits - 1);  // the root's mid-planes
  for (int octant = 0; octant < 8; ++octant) {
    const QRay ray{uint32_t(octant), {mid - 77, mid + 31, mid + 5},
                   {(octant & 4) ? -kDirMax : kDirMax, (octant & 2) ? -kDirMax / 3 : kDirMax / 3,
                    (octant & 1) ? -kDirMax / 5 : kDirMax / 5}};
    EXPECT_EQ(traverseOctree(image, ray).hit, bruteForceHit(tris, ray)) << "octant " << octant;
  }
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {1, -1}) {
      for (int64_t at : {mid, mid - 1, int64_t(0), kPosMax, mid / 2}) {  // in the mid-planes and off them
        QRay ray{0, {at, at, at}, {0, 0, 0}};
        ray.dir[axis] = sign * kDirMax;
        const OctreeTrace trace = traverseOctree(image, ray);
        EXPECT_EQ(trace.hit, bruteForceHit(tris, ray)) << "axis " << axis << " sign " << sign << " at " << at;
      }
    }
  }
}

TEST(GoldenOctree, RaysThroughTheCentreAndNodeCornersAndEdges) {
  const auto tris = quantizeScene(loadScene(test::kBunny));
  const OctreeImage image = buildOctreeImage(tris, 8, 4);
  const int64_t s = int64_t(1) << kPosBits;
  std::mt19937_64 rng(17);
  std::uniform_int_distribution<int> level(1, 6), cell(0, 63);
  for (uint32_t i = 0; i < 600; ++i) {
    // A node corner at some depth, and a direction through another corner or along an edge.
    const int64_t step = s >> level(rng);
    const std::array<int64_t, 3> corner{std::min<int64_t>(kPosMax, cell(rng) % (s / step) * step),
                                        std::min<int64_t>(kPosMax, cell(rng) % (s / step) * step),
                                        std::min<int64_t>(kPosMax, cell(rng) % (s / step) * step)};
    std::array<int64_t, 3> dir{kDirMax, (i % 3 == 0) ? 0 : kDirMax, (i % 2) ? kDirMax : -kDirMax};
    if (i % 5 == 0) dir = {-kDirMax, -kDirMax, -kDirMax};
    const QRay ray{i, corner, dir};
    ASSERT_EQ(traverseOctree(image, ray).hit, bruteForceHit(tris, ray)) << "ray " << i;
  }
  // Through the centre of the root along the main diagonal, both ways.
  const int64_t c = s / 2;
  for (int64_t sign : {1, -1}) {
    const QRay ray{0, {c, c, c}, {sign * kDirMax, sign * kDirMax, sign * kDirMax}};
    EXPECT_EQ(traverseOctree(image, ray).hit, bruteForceHit(tris, ray));
  }
}

TEST(GoldenOctree, SceneNotCentredOnTheOriginMirrorsCorrectly) {
  // Far from the world origin and off-centre in the lattice: only min + max - o
  // mirroring gives the right children for negative directions.
  const Scene scene = translated(loadScene(test::kBunny), {1000.0f, -500.0f, 250.0f});
  const auto tris = quantizeScene(scene);
  const OctreeImage image = buildOctreeImage(tris, 7, 4);
  std::mt19937_64 rng(23);
  for (uint32_t i = 0; i < 500; ++i) {
    QRay ray = randomLatticeRay(rng, i);
    for (auto& d : ray.dir) d = -std::llabs(d);  // all negative: every axis mirrored
    ASSERT_EQ(traverseOctree(image, ray).hit, bruteForceHit(tris, ray)) << "ray " << i;
  }
}

TEST(GoldenOctree, MaximumDepthWithTinyNodesAndExactHalvings) {
  // A cluster of tiny triangles forces leaves one lattice unit wide.
  std::vector<QTriangle> tris;
  const int64_t base = (int64_t(1) << kPosBits) / 3;
  for (uint32_t i = 0; i < 40; ++i) {
    const int64_t x = base + i % 5, y = base + i / 5 % 4, z = base + i / 20;
    tris.push_back(QTriangle{i, {{{x, y, z}, {x + 1, y, z}, {x, y + 1, z + 1}}}});
  }
  const OctreeImage image = buildOctreeImage(tris, kOctreeMaxDepth, 1);
  EXPECT_GE(image.depth, kOctreeMaxDepth - 2) << "the build must reach nodes a unit or two wide";
  std::mt19937_64 rng(29);
  std::uniform_int_distribution<int64_t> near(base - 3, base + 8);
  for (uint32_t i = 0; i < 400; ++i) {
    QRay ray = randomLatticeRay(rng, i);
    ray.org = {near(rng), near(rng), near(rng)};
    ASSERT_EQ(traverseOctree(image, ray).hit, bruteForceHit(tris, ray)) << "ray " << i;
  }
}

TEST(GoldenOctree, DeepSparseAndFullTrees) {
  // Sparse: one small triangle in a corner; the walk passes many empty nodes.
  const std::vector<QTriangle> one{QTriangle{0, {{{10, 10, 10}, {20, 10, 10}, {10, 20, 12}}}}};
  const OctreeImage sparse = buildOctreeImage(one, 10, 0 + 1);
  const QRay toward{0, {kPosMax, kPosMax, 11}, {-kDirMax, -kDirMax, 0}};
  const OctreeTrace t = traverseOctree(sparse, toward);
  EXPECT_EQ(t.hit, bruteForceHit(one, toward));
  // Full: the Cornell box subdivided, split as deep as the triangles allow.
  const auto tris = quantizeScene(subdivide(makeCornellBox(), 3));
  const OctreeImage full = buildOctreeImage(tris, 9, 1);
  std::mt19937_64 rng(31);
  for (uint32_t i = 0; i < 200; ++i) {
    const QRay ray = randomLatticeRay(rng, i);
    ASSERT_EQ(traverseOctree(full, ray).hit, bruteForceHit(tris, ray)) << "ray " << i;
  }
}

TEST(GoldenOctree, EarlyTerminationStopsInTheLeafHoldingTheHit) {
  const auto tris = quantizeScene(makeCornellBox());
  const OctreeImage image = buildOctreeImage(tris, 6, 2);
  // From the front of the box straight at the back wall: the walk must stop
  // once the back wall's hit is inside the current leaf, well before leaving the root.
  const int64_t mid = int64_t(1) << (kPosBits - 1);
  const QRay ray{0, {mid, mid, 0}, {0, 0, kDirMax}};
  const OctreeTrace trace = traverseOctree(image, ray);
  ASSERT_TRUE(trace.hit.has_value());
  EXPECT_EQ(trace.hit, bruteForceHit(tris, ray));
}

TEST(GoldenOctree, TablesFollowThePaper) {
  // nextChild: exit plane x from child 0 goes to 4, y to 2, z to 1; from 7 always leaves.
  const OctT a{1, 0}, b{2, 0}, c{3, 0};
  EXPECT_EQ(nextChild(0, {a, b, c}), 4);
  EXPECT_EQ(nextChild(0, {b, a, c}), 2);
  EXPECT_EQ(nextChild(0, {b, c, a}), 1);
  EXPECT_EQ(nextChild(5, {a, b, c}), 8);
  EXPECT_EQ(nextChild(5, {b, a, c}), 7);
  for (int axis = 0; axis < 3; ++axis) {
    std::array<OctT, 3> t{c, c, c};
    t[axis] = a;
    EXPECT_EQ(nextChild(7, t), 8);
  }
  // firstChild: entering through the YZ plane (largest t0 on x) at t0x = 5,
  // with the y mid-plane crossed before it, starts in a child with the y bit set.
  EXPECT_EQ(firstChild({OctT{5, 0}, OctT{1, 0}, OctT{2, 0}}, {OctT{9, 0}, OctT{4, 0}, OctT{7, 0}}), 2);
}

TEST(GoldenOctree, BadConfigurationsAreErrors) {
  const auto tris = quantizeScene(makeCornellBox());
  EXPECT_THROW(buildOctreeImage(tris, 0, 8), InputError);
  try {
    buildOctreeImage(tris, kOctreeMaxDepth + 1, 8);
    FAIL() << "expected a depth error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("position format"), std::string::npos) << e.what();
  }
  EXPECT_THROW(buildOctreeImage(tris, 4, 0), InputError);
  EXPECT_GE(defaultOctreeDepth(3674), 1);
  // The address-width check every unit's image builder uses, at a width small
  // enough to reach: the octree of the Cornell box at depth 4 has 73 nodes.
  const OctreeImage image = buildOctreeImage(tris, 4, 8);
  EXPECT_NO_THROW(checkRegionFits("octree", "node table", image.nodes.size(), "", 7));
  try {
    checkRegionFits("octree", "node table", image.nodes.size(), "lower --octree-depth", 6);
    FAIL() << "expected the node table not to fit 6 address bits";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("octree's memory image does not fit the 6-bit address width: the node "
                                         "table needs 73 entries (at most 64); lower --octree-depth"),
              std::string::npos)
        << e.what();
  }
  EXPECT_LE(defaultOctreeDepth(100000000), kOctreeMaxDepth);
}

}  // namespace
}  // namespace lancer::fx
