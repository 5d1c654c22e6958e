#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <random>

#include "common/error.h"
#include "driver/quantize.h"
#include "golden/isect.h"
#include "golden/memory_image.h"
#include "golden/octree.h"
#include "golden/octree_unit.h"
#include "scene/scene.h"
#include "support/structure_test_support.h"
#include "support/test_paths.h"
#include "support/octree_cases.h"
#include "support/traversal_cases.h"
#include "support/treelet_walks.h"

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

// ---- The treelet layout and the walk set aside (docs/scheduling.md) ---------------

// The octree's walk for test::walkBlockByBlock.
struct OctreeWalkOps {
  using Image = OctreeImage;
  using Walk = OctreeWalk;
  static constexpr int window = kOctreeSuspendLevels;
  static Walk start(const Image& image) { return startOctreeWalk(image); }
  static void resume(const Image& image, const QRay& ray, Walk& walk, uint32_t block) {
    continueOctreeWalk(image, ray, walk, block);
  }
  static Walk carry(const Walk& walk, const QRay& ray) { return octreeWalkOf(octreeWalkValues(walk), ray); }
  static TraversalTrace traverse(const Image& image, const QRay& ray) { return traverseOctree(image, ray); }
  static TreeletCrossings crossings(const Image& image, const QRay& ray) { return octreeTreeletCrossings(image, ray); }
};

// On every hard case a walk set aside before every descent (each child group
// its own block) and resumed, its record carried through octree_walk_t, takes
// the unbroken walk; without a layout nothing is set aside.
TEST(GoldenOctreeTreelets, AWalkSetAsideAtEveryGroupTakesTheUnbrokenWalk) {
  for (test::OctreeCase& c : test::octreeHardCases()) {
    EXPECT_EQ(test::walkBlockByBlock<OctreeWalkOps>(c.image, c.rays), 0u) << c.name << ": no layout, no suspension";
    if (c.image.nodes[0].leaf) continue;
    layoutOctreeTreelets(c.image, kOctreeChildren);
    test::walkBlockByBlock<OctreeWalkOps>(c.image, c.rays);
    if (::testing::Test::HasFailure()) FAIL() << c.name;
  }
}

class GoldenOctreeTreeletLayout : public ::testing::TestWithParam<uint32_t> {};

// The layout renumbers nodes and primitives and changes nothing a ray finds:
// the same hit, as many nodes entered and tests issued. Every group is whole
// in one aligned block; the root keeps entry 0; padding is never referenced.
TEST_P(GoldenOctreeTreeletLayout, EveryRayWalksTheSameTreeToTheSameHit) {
  static const std::vector<QTriangle> tris = quantizeScene(loadScene(test::kBunny));
  const uint32_t blockNodes = GetParam();
  const OctreeImage plain = buildOctreeImage(tris, std::min(7, kOctreeMaxDepth), 4);
  OctreeImage image = plain;
  layoutOctreeTreelets(image, blockNodes);
  EXPECT_EQ(image.treeletNodes, blockNodes);
  EXPECT_EQ(image.nodes.size() % kOctreeChildren, 0u);
  EXPECT_EQ(image.nodes.size(), plain.nodes.size() + image.paddingNodes);
  EXPECT_EQ(image.indices.size(), plain.indices.size());
  EXPECT_GE(image.treelets, (plain.nodes.size() / kOctreeChildren + blockNodes / kOctreeChildren - 1) /
                                (blockNodes / kOctreeChildren));
  std::vector<int> referenced(image.nodes.size(), 0);
  referenced[0] = 1;
  uint32_t listed = 0;
  for (uint32_t i = 0; i < image.nodes.size(); ++i) {
    const OctreeNode& n = image.nodes[i];
    if (n.leaf) {
      EXPECT_EQ(n.first, n.count ? listed : n.first) << "node " << i << ": the index list in node-table order";
      listed += n.count;
      EXPECT_TRUE(std::is_sorted(image.indices.begin() + n.first, image.indices.begin() + n.first + n.count));
      continue;
    }
    ASSERT_EQ(n.first % kOctreeChildren, 0u) << "node " << i << ": a group starts on a multiple of 8";
    EXPECT_EQ(image.blockOf(n.first), image.blockOf(n.first + kOctreeChildren - 1)) << "a group in one block";
    for (uint32_t c = 0; c < kOctreeChildren; ++c) ++referenced[n.first + c];
  }
  size_t padding = 0;
  for (uint32_t i = 0; i < image.nodes.size(); ++i) {
    EXPECT_LE(referenced[i], 1) << "node " << i << " has two parents";
    if (referenced[i] == 0) {
      ++padding;
      EXPECT_EQ(image.nodes[i], (OctreeNode{true, 0, 0})) << "padding node " << i;
    }
  }
  EXPECT_EQ(padding, image.paddingNodes);
  std::mt19937_64 rng{blockNodes};
  for (uint32_t i = 0; i < 300; ++i) {
    const QRay ray = randomLatticeRay(rng, i);
    const OctreeTrace a = traverseOctree(plain, ray), b = traverseOctree(image, ray);
    ASSERT_EQ(b.hit, a.hit) << "ray " << i;
    ASSERT_EQ(b.visits.size(), a.visits.size()) << "ray " << i;
    ASSERT_EQ(b.tests, a.tests) << "ray " << i;
  }
}
INSTANTIATE_TEST_SUITE_P(BlockSizes, GoldenOctreeTreeletLayout, ::testing::Values(8u, 16u, 64u, 512u, 4096u));

// With every group its own block, every group read but the first (the root's
// group, in the block a fresh walk starts in) is a crossing, and every descent
// but the root's a suspension (a refill never is); with one block for the
// whole tree, nothing is.
TEST(GoldenOctreeTreelets, CrossingsAreTheGroupReadsInAnotherBlock) {
  const std::vector<QTriangle> tris = quantizeScene(makeCornellBox());
  const OctreeImage plain = buildOctreeImage(tris, std::min(6, kOctreeMaxDepth), 1);
  OctreeImage single = plain, whole = plain;
  layoutOctreeTreelets(single, kOctreeChildren);
  layoutOctreeTreelets(whole, std::bit_ceil(uint32_t(plain.nodes.size() + kOctreeChildren)));
  const OctreeUnit::NodeReads reads(single);
  std::mt19937_64 rng{5};
  TreeletCrossings all;
  for (uint32_t i = 0; i < 300; ++i) {
    const QRay ray = randomLatticeRay(rng, i);
    EXPECT_EQ(octreeTreeletCrossings(plain, ray).rays, 0u) << "no layout, nothing counted";
    EXPECT_EQ(octreeTreeletCrossings(whole, ray).crossings, 0u);
    const OctreeTrace trace = traverseOctree(single, ray);
    const uint64_t groupReads = reads(trace);
    const uint64_t descents = uint64_t(std::count_if(trace.visits.begin(), trace.visits.end(),
                                                     [&](uint32_t node) { return !single.nodes[node].leaf; }));
    const TreeletCrossings c = octreeTreeletCrossings(single, ray);
    ASSERT_EQ(c.rays, 1u);
    ASSERT_EQ(c.crossings, groupReads > 0 ? groupReads - 1 : 0) << "ray " << i;
    ASSERT_EQ(c.suspensions, descents > 0 ? descents - 1 : 0) << "ray " << i << " (a depth-6 tree fits the window)";
    ASSERT_GE(c.stateBits, c.suspensions * uint64_t(octreeSuspendedBits(0)));
    all += c;
  }
  EXPECT_GT(all.crossings, 300u);
  EXPECT_GT(all.crossings, all.suspensions) << "some walks go back up";
}

TEST(GoldenOctreeTreelets, SuspendedWalksResumedBlockByBlockTakeTheUnbrokenWalk) {
  static const std::vector<QTriangle> tris = quantizeScene(loadScene(test::kBunny));
  for (const uint32_t blockNodes : {8u, 64u, 1024u}) {
    OctreeImage image = buildOctreeImage(tris, std::min(7, kOctreeMaxDepth), 4);
    layoutOctreeTreelets(image, blockNodes);
    const std::vector<QRay> rays = test::treeletRays(blockNodes, 400);
    const uint64_t suspensions = test::checkBlockByBlock<OctreeWalkOps>(image, rays);
    if (blockNodes == 8) {
      EXPECT_GT(suspensions, rays.size());
    }
  }
}

// A read with more levels on the stack than the window is a crossing, not a
// suspension: the walk goes on into the other block. The walk to two tiny
// triangles a few units apart goes down to where they part.
TEST(GoldenOctreeTreelets, AReadWithAStackDeeperThanTheWindowGoesOn) {
  const std::vector<QTriangle> two{QTriangle{0, {{{10, 10, 10}, {11, 10, 10}, {10, 11, 10}}}},
                                   QTriangle{1, {{{14, 14, 14}, {15, 14, 14}, {14, 15, 14}}}}};
  OctreeImage image = buildOctreeImage(two, kOctreeMaxDepth, 1);  // they part only in nodes a few units wide
  if (image.depth <= kOctreeSuspendLevels + 1) GTEST_SKIP() << "the formats' octrees fit the window";
  layoutOctreeTreelets(image, kOctreeChildren);
  const std::vector<QRay> rays = {QRay{.id = 0, .org = {0, 0, 0}, .dir = {kDirMax, kDirMax, kDirMax}},
                                  QRay{.id = 1, .org = {10, 10, 0}, .dir = {1, 1, kDirMax}}};
  for (const QRay& ray : rays) {
    const TreeletCrossings c = octreeTreeletCrossings(image, ray);
    EXPECT_GT(c.crossings, c.suspensions) << "ray " << ray.id;
    EXPECT_GT(c.suspensions, 0u) << "ray " << ray.id;
  }
  test::walkBlockByBlock<OctreeWalkOps>(image, rays);
}

TEST(GoldenOctreeTreelets, TheBudgetIsAtLeastOneGroupAndBlocksArePowersOfTwo) {
  const std::vector<QTriangle> tris = quantizeScene(makeCornellBox());
  OctreeImage image = buildOctreeImage(tris, 4, 2);
  EXPECT_THROW(layoutOctreeTreelets(image, 4), InputError);
  EXPECT_THROW(layoutOctreeTreelets(image, 24), InputError);
  AccelOptions options;
  options.octreeTreeletBytes = int(OctreeUnit::kGroupBytes) - 1;
  try {
    OctreeUnit::build(tris, options);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              fmt::format("--octree-treelet-bytes {}: a treelet holds at least one child group ({} bytes)",
                          OctreeUnit::kGroupBytes - 1, OctreeUnit::kGroupBytes));
  }
  options.octreeTreeletBytes = int(OctreeUnit::kGroupBytes) * 5;  // 40 nodes: blocks of 32
  EXPECT_EQ(OctreeUnit::build(tris, options).treeletNodes, 32u);
}

}  // namespace
}  // namespace lancer::fx
