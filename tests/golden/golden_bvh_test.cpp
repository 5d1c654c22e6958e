#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <deque>
#include <functional>
#include <map>
#include <random>
#include <span>

#include <fmt/format.h>

#include "common/error.h"
#include "golden/bvh.h"
#include "golden/bvh_unit.h"
#include "golden/isect.h"
#include "golden/wide.h"
#include "scene/scene.h"
#include "support/bvh_cases.h"
#include "support/test_paths.h"
#include "support/traversal_cases.h"
#include "support/treelet_walks.h"

namespace lancer::fx {
namespace {
using namespace lancer::test;  // quantizeScene, bruteForceHit, randomLatticeRay (support/traversal_cases.h)

// ---- The exact answer of a ray-box test, by rationals on the unmirrored ray ---------
// t in [max t0, min t1] over the axes the ray crosses, each t = num / den with
// den > 0; compared by cross-multiplication.
struct Frac {
  i128 num = 0, den = 1;
  bool operator<(const Frac& o) const { return num * o.den < o.num * den; }
  bool operator<=(const Frac& o) const { return !(o < *this); }
};

struct ExactBox {
  bool hit = false;
  Frac entry;  // max(t_min, 0)
};

ExactBox exactBoxTest(const QRay& ray, const std::array<int64_t, 3>& lo, const std::array<int64_t, 3>& hi) {
  std::optional<Frac> tmin, tmax;
  for (int a = 0; a < 3; ++a) {
    const int64_t d = ray.dir[a], o = ray.org[a];
    if (d == 0) {
      if (o < lo[a] || o > hi[a]) return {};
      continue;
    }
    Frac t0{i128(lo[a] - o), i128(d)}, t1{i128(hi[a] - o), i128(d)};
    if (d < 0) {
      t0 = {-t0.num, -t0.den};
      t1 = {-t1.num, -t1.den};
      std::swap(t0, t1);
    }
    if (!tmin || *tmin < t0) tmin = t0;
    if (!tmax || t1 < *tmax) tmax = t1;
  }
  // Some point of the closed box at t > 0.
  if (!(*tmin <= *tmax) || !(Frac{0, 1} < *tmax)) return {};
  return ExactBox{true, *tmin < Frac{0, 1} ? Frac{0, 1} : *tmin};
}

void expectSameAsExact(const QRay& ray, const std::array<int64_t, 3>& lo, const std::array<int64_t, 3>& hi,
                       const std::string& what) {
  const BvhRaySetup setup = BvhRaySetup::setup(ray);
  const BoxHit got = boxTest(setup, lo, hi);
  const ExactBox want = exactBoxTest(ray, lo, hi);
  ASSERT_EQ(got.hit, want.hit) << what;
  if (!want.hit) return;
  // entry / common == the exact entry parameter.
  ASSERT_EQ(i128(got.entry) * want.entry.den, want.entry.num * i128(setup.common)) << what;
}

TEST(GoldenBvhBoxTest, EqualsExactArithmeticOnRandomBoxesAndRays) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int64_t> pos(0, kPosMax);
  for (uint32_t i = 0; i < 20000; ++i) {
    QRay ray = randomLatticeRay(rng, i);
    if (i % 4 == 1) ray.dir[(i / 4) % 3] = 0;  // a slab the ray never crosses
    if (i % 4 == 2) {                           // axis-parallel
      const int k = dominantAxis(ray.dir);
      for (int a = 0; a < 3; ++a) ray.dir[a] = a == k ? ray.dir[a] : 0;
    }
    std::array<int64_t, 3> lo{}, hi{};
    for (int a = 0; a < 3; ++a) {
      lo[a] = pos(rng);
      hi[a] = i % 7 == 0 ? lo[a] : std::min<int64_t>(kLatticeSide + 100, lo[a] + pos(rng) / 8);  // flat boxes too
    }
    expectSameAsExact(ray, lo, hi, "ray " + std::to_string(i));
  }
}

TEST(GoldenBvhBoxTest, EqualsExactArithmeticOnHardRays) {
  // Origins on the box's faces, edges and corners; rays through its corners,
  // along its edges and grazing its faces; tiny direction components.
  const std::array<int64_t, 3> lo{1000, 2000, 3000}, hi{5000, 2000, 9000};  // flat in y
  std::vector<std::array<int64_t, 3>> points;
  for (int64_t x : {lo[0], hi[0], (lo[0] + hi[0]) / 2, lo[0] - 1, hi[0] + 1})
    for (int64_t y : {lo[1], lo[1] - 1, lo[1] + 1})
      for (int64_t z : {lo[2], hi[2], (lo[2] + hi[2]) / 2, hi[2] + 1}) points.push_back({x, y, z});
  uint32_t id = 0;
  for (const auto& from : points) {
    for (const auto& to : points) {
      if (from == to) continue;
      std::array<int64_t, 3> d{to[0] - from[0], to[1] - from[1], to[2] - from[2]};
      // Scale so the dominant component is +-kDirMax while staying exact where it can.
      const int k = dominantAxis(d);
      const int64_t m = std::llabs(d[k]);
      for (int a = 0; a < 3; ++a) d[a] = d[a] * kDirMax / m;
      if (d[0] == 0 && d[1] == 0 && d[2] == 0) continue;
      expectSameAsExact(QRay{id++, from, d}, lo, hi, fmt::format("ray {}", id));
    }
    for (int axis = 0; axis < 3; ++axis) {
      for (int sign : {1, -1}) {
        for (int64_t tiny : {int64_t(0), int64_t(1), int64_t(-1)}) {
          std::array<int64_t, 3> d{tiny, tiny, tiny};
          d[axis] = sign * kDirMax;
          expectSameAsExact(QRay{id++, from, d}, lo, hi, fmt::format("axis ray {}", id));
        }
      }
    }
  }
}

// ---- The image --------------------------------------------------------------------------
// Calls fn(triangle id, quantized boxes of every ancestor's child on the path) for each triangle.
void forEachLeafTriangle(const BvhImage& image, const BvhRef& ref, std::vector<LatticeBox>& path,
                         const std::function<void(uint32_t, const std::vector<LatticeBox>&)>& fn) {
  if (ref.leaf) {
    for (uint32_t k = 0; k < ref.count; ++k) fn(image.indices[ref.first + k], path);
    return;
  }
  const BvhNode& node = image.nodes[ref.first];
  for (int c = 0; c < kBvhWidth; ++c) {
    path.push_back(LatticeBox{node.childLo(c), node.childHi(c)});
    forEachLeafTriangle(image, node.child[c], path, fn);
    path.pop_back();
  }
}

TEST(GoldenBvhImage, QuantizedChildBoxesHoldEveryTriangleBelowThem) {
  const auto tris = quantizeScene(loadScene(test::kBunny));
  const BvhImage image = buildBvhImage(tris, 4);
  std::vector<LatticeBox> path;
  size_t listed = 0;
  forEachLeafTriangle(image, image.root, path, [&](uint32_t id, const std::vector<LatticeBox>& boxes) {
    ++listed;
    const LatticeBox t = latticeBounds(tris[id]);
    for (const LatticeBox& b : boxes) {
      for (int a = 0; a < 3; ++a) {
        ASSERT_LE(b.lo[a], t.lo[a]) << "triangle " << id;
        ASSERT_GE(b.hi[a], t.hi[a]) << "triangle " << id;
      }
    }
  });
  EXPECT_EQ(listed, tris.size()) << "every triangle in exactly one leaf";
  EXPECT_LE(image.depth, kBvhMaxLevels);
  for (const BvhNode& node : image.nodes) {
    for (int c = 0; c < kBvhWidth; ++c) {
      for (int a = 0; a < 3; ++a) {
        EXPECT_LE(node.lo[c][a], uint32_t(kBvhPlaneMax));
        EXPECT_LE(node.hi[c][a], uint32_t(kBvhPlaneMax));
      }
    }
  }
}

TEST(GoldenBvhImage, PlaneQuantizationRoundsOutwards) {
  for (int64_t extent : {0, 1, 254, 255, 256, 1000, 65535}) {
    const int s = bvhShiftFor(extent);
    EXPECT_GE(int64_t(kBvhPlaneMax) << s, extent);
    if (s > 0) {
      EXPECT_LT(int64_t(kBvhPlaneMax) << (s - 1), extent);
    }
    for (int64_t p = 0; p <= extent; p += std::max<int64_t>(1, extent / 97)) {
      EXPECT_LE(int64_t(bvhPlaneDown(p + 7, 7, s)) << s, p);
      EXPECT_GE(int64_t(bvhPlaneUp(p + 7, 7, s)) << s, p);
      EXPECT_LE(bvhPlaneUp(p + 7, 7, s), uint32_t(kBvhPlaneMax));
    }
  }
}

// ---- The walk ------------------------------------------------------------------------------
class GoldenBvhLeaves : public ::testing::TestWithParam<int> {};

TEST_P(GoldenBvhLeaves, ClosestHitEqualsBruteForceOnTheBunny) {
  static const std::vector<QTriangle> tris = quantizeScene(loadScene(test::kBunny));
  const BvhImage image = buildBvhImage(tris, GetParam());
  std::mt19937_64 rng{uint64_t(GetParam())};
  for (uint32_t i = 0; i < 400; ++i) {
    const QRay ray = randomLatticeRay(rng, i);
    const TraversalTrace trace = traverseBvh(image, ray);
    ASSERT_EQ(trace.hit, bruteForceHit(tris, ray)) << "ray " << i << " leaf " << GetParam();
    ASSERT_FALSE(trace.visits.empty());
    EXPECT_EQ(trace.visits.front(), image.root.visitId()) << "the walk starts at the root";
  }
}
INSTANTIATE_TEST_SUITE_P(LeafSizes, GoldenBvhLeaves, ::testing::Values(1, 2, 4, 8, 32));

TEST(GoldenBvh, AxisParallelOctantAndCornerRaysOnTheCornellBox) {
  const auto tris = quantizeScene(makeCornellBox());
  const BvhImage image = buildBvhImage(tris, 2);
  const int64_t mid = kLatticeSide / 2;
  for (int octant = 0; octant < 8; ++octant) {
    const QRay ray{uint32_t(octant), {mid - 77, mid + 31, mid + 5},
                   {(octant & 4) ? -kDirMax : kDirMax, (octant & 2) ? -kDirMax / 3 : kDirMax / 3,
                    (octant & 1) ? -kDirMax / 5 : kDirMax / 5}};
    EXPECT_EQ(traverseBvh(image, ray).hit, bruteForceHit(tris, ray)) << "octant " << octant;
  }
  // From every vertex and box corner of the scene towards others: rays through
  // triangle corners and edges, box corners, in box faces.
  std::vector<std::array<int64_t, 3>> points;
  for (const QTriangle& t : tris)
    for (const auto& v : t.v) points.push_back(v);
  for (const BvhNode& node : image.nodes)
    for (int c = 0; c < kBvhWidth; ++c) {
      auto hi = node.childHi(c);
      for (auto& h : hi) h = std::min(h, kPosMax);
      points.push_back(node.childLo(c));
      points.push_back(hi);
    }
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<size_t> pick(0, points.size() - 1);
  for (uint32_t i = 0; i < 3000; ++i) {
    const auto from = points[pick(rng)], to = points[pick(rng)];
    std::array<int64_t, 3> d{to[0] - from[0], to[1] - from[1], to[2] - from[2]};
    if (i % 3 == 0) d = {0, 0, 0}, d[i % 9 / 3] = (i & 8) ? kDirMax : -kDirMax;  // axis-parallel from a vertex
    const int k = dominantAxis(d);
    if (d[k] == 0) continue;
    const int64_t m = std::llabs(d[k]);
    for (int a = 0; a < 3; ++a) d[a] = d[a] * kDirMax / m;
    const QRay ray{i, from, d};
    ASSERT_EQ(traverseBvh(image, ray).hit, bruteForceHit(tris, ray)) << "ray " << i;
  }
}

TEST(GoldenBvh, NearerChildFirstAndCulledBeyondTheHit) {
  const auto tris = quantizeScene(loadScene(test::kBunny));
  const BvhImage image = buildBvhImage(tris, 4);
  std::mt19937_64 rng(9);
  uint64_t culledRays = 0, orderedPairs = 0;
  for (uint32_t i = 0; i < 300; ++i) {
    const QRay ray = randomLatticeRay(rng, i);
    const TraversalTrace trace = traverseBvh(image, ray);
    const BvhRaySetup setup = BvhRaySetup::setup(ray);
    // After an interior node, the walk enters the child nearer by entry
    // (child 0 on a tie), unless the bound culls it.
    for (size_t k = 0; k + 1 < trace.visits.size(); ++k) {
      if (trace.visits[k] & kBvhLeafVisit) continue;
      const BvhNode& node = image.nodes[trace.visits[k]];
      const BoxHit h0 = boxTest(setup, node.childLo(0), node.childHi(0));
      const BoxHit h1 = boxTest(setup, node.childLo(1), node.childHi(1));
      if (!(h0.hit && h1.hit)) continue;
      const int near = h1.entry < h0.entry ? 1 : 0;
      if (trace.visits[k + 1] == node.child[near].visitId()) ++orderedPairs;
      // (With a hit, the nearer child may be culled and the farther popped next.)
      if (!trace.hit) {
        ASSERT_NE(trace.visits[k + 1], node.child[1 - near].visitId()) << "ray " << i;
      }
    }
    // Every box the ray enters, against the ones the walk entered.
    uint64_t everyBox = 0;
    std::function<void(const BvhRef&)> count = [&](const BvhRef& ref) {
      ++everyBox;
      if (ref.leaf) return;
      const BvhNode& node = image.nodes[ref.first];
      for (int c = 0; c < kBvhWidth; ++c)
        if (boxTest(setup, node.childLo(c), node.childHi(c)).hit) count(node.child[c]);
    };
    count(image.root);
    EXPECT_LE(trace.visits.size(), everyBox);
    if (trace.hit && trace.visits.size() < everyBox) ++culledRays;
  }
  EXPECT_GT(orderedPairs, 100u);
  EXPECT_GT(culledRays, 0u) << "the closest hit culls boxes behind it";
}

TEST(GoldenBvh, AnyHitAndSegmentEnds) {
  const auto tris = quantizeScene(loadScene(test::kBunny));
  const BvhImage image = buildBvhImage(tris, 4);
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<uint64_t> end(0, uint64_t(kLatticeSide) << kSegFracBits);
  uint64_t closestTests = 0, anyTests = 0, hits = 0;
  for (uint32_t i = 0; i < 600; ++i) {
    QRay ray = randomLatticeRay(rng, i);
    ray.tMax = end(rng);
    const auto want = bruteForceHit(tris, ray);  // intersect() honours the segment end
    const TraversalTrace closest = traverseBvh(image, ray);
    ASSERT_EQ(closest.hit, want) << "ray " << i;
    ray.anyHit = true;
    const TraversalTrace any = traverseBvh(image, ray);
    ASSERT_EQ(any.hit.has_value(), want.has_value()) << "ray " << i;
    if (any.hit) {
      ++hits;
      EXPECT_TRUE(intersect(ray, tris[any.hit->primId]) == *any.hit) << "a true hit on the segment";
    }
    closestTests += closest.tests;
    anyTests += any.tests;
  }
  EXPECT_GT(hits, 50u);
  EXPECT_LT(anyTests, closestTests) << "any-hit stops at the first hit";
}

TEST(GoldenBvh, NodeReadsAreTheInteriorNodesEntered) {
  const auto tris = quantizeScene(makeCornellBox());
  const BvhImage image = buildBvhImage(tris, 1);
  std::mt19937_64 rng(2);
  const BvhUnit::NodeReads reads(image);
  for (uint32_t i = 0; i < 100; ++i) {
    const TraversalTrace trace = traverseBvh(image, randomLatticeRay(rng, i));
    uint64_t interior = 0;
    for (uint32_t id : trace.visits) interior += (id & kBvhLeafVisit) == 0;
    EXPECT_EQ(reads(trace), interior);
  }
}

TEST(GoldenBvh, EmptySceneAndRootLeaf) {
  const BvhImage empty = buildBvhImage({}, 4);
  EXPECT_TRUE(empty.root.leaf);
  const QRay ray{0, {1, 2, 3}, {kDirMax, 1, 1}};
  const TraversalTrace none = traverseBvh(empty, ray);
  EXPECT_FALSE(none.hit);
  EXPECT_EQ(none.visits, std::vector<uint32_t>{kBvhLeafVisit});
  const auto tris = quantizeScene(makeCornellBox());
  const std::vector<QTriangle> two(tris.begin(), tris.begin() + 2);
  const BvhImage leaf = buildBvhImage(two, 4);
  std::mt19937_64 rng(1);
  for (uint32_t i = 0; i < 50; ++i) {
    const QRay r = randomLatticeRay(rng, i);
    EXPECT_EQ(traverseBvh(leaf, r).hit, bruteForceHit(two, r));
  }
}

// A chain whose interior child is always nearer (equal entries: child 0 first)
// pushes its leaf sibling at every level.
BvhImage chainImage(int levels) {
  const auto tris = quantizeScene(makeCornellBox());
  BvhImage image;
  image.leafSize = 1;
  image.triangles = tris;
  image.indices = {0};
  const int shift = bvhShiftFor(kLatticeSide);
  for (int k = 0; k + 1 < levels; ++k) {
    BvhNode node;
    node.shift = {shift, shift, shift};
    for (int c = 0; c < kBvhWidth; ++c) node.hi[c] = {kBvhPlaneMax, kBvhPlaneMax, kBvhPlaneMax};
    node.child[0] = k + 2 < levels ? BvhRef{false, 0, uint32_t(k + 1)} : BvhRef{true, 1, 0};
    node.child[1] = BvhRef{true, 1, 0};
    image.nodes.push_back(node);
  }
  image.root = BvhRef{false, 0, 0};
  image.depth = levels;
  return image;
}

TEST(GoldenBvh, StackDepthIsTheLevelsLimitAndOverflowIsRefused) {
  const QRay ray{0, {5, 5, 5}, {kDirMax, 3, 7}};
  const TraversalTrace deepest = traverseBvh(chainImage(kBvhMaxLevels), ray);
  EXPECT_EQ(deepest.visits.size(), size_t(kBvhMaxLevels + kBvhMaxLevels - 1)) << "every node and leaf entered";
  EXPECT_NO_THROW(BvhUnit::checkImage(chainImage(kBvhMaxLevels), {}));
  const BvhImage tooDeep = chainImage(kBvhMaxLevels + 1);
  EXPECT_THROW(traverseBvh(tooDeep, ray), std::logic_error);
  try {
    BvhUnit::checkImage(tooDeep, {});
    FAIL() << "a too-deep image is refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("exceeds the unit's stack"), std::string::npos) << e.what();
  }
}

TEST(GoldenBvh, BadConfigurationsAreErrors) {
  EXPECT_THROW(buildBvhImage({}, 0), InputError);
  EXPECT_THROW(buildBvhImage({}, kBvhMaxLeafSize + 1), InputError);
  const BvhImage image = buildBvhImage(quantizeScene(makeCornellBox()), 4);
  const QRay zero{7, {1, 2, 3}, {0, 0, 0}};
  try {
    BvhUnit::checkImage(image, std::span<const QRay>(&zero, 1));
    FAIL() << "a zero direction is refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ray 7"), std::string::npos) << e.what();
  }
}

TEST(GoldenBvh, AnImageBeyondTheAddressWidthIsOneLineError) {
  // No scene a test can build reaches kMemAddrBits (2^24 nodes), so the check
  // buildBvhImage runs is run at widths the Cornell box's 32 triangles exceed.
  const BvhImage image = buildBvhImage(quantizeScene(makeCornellBox()), 4);
  ASSERT_EQ(image.triangles.size(), 32u);
  EXPECT_NO_THROW(checkBvhImageFits(image, 5));
  auto messageAt = [&](int addrBits) {
    try {
      checkBvhImageFits(image, addrBits);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string indices = messageAt(4);
  EXPECT_NE(indices.find("the bvh's memory image does not fit the 4-bit address width: the index list needs 32 "
                         "entries (at most 16); use a smaller scene"),
            std::string::npos)
      << indices;
  EXPECT_EQ(indices.find('\n'), std::string::npos) << "one line";
  const std::string nodes = messageAt(1);
  EXPECT_NE(nodes.find(fmt::format("the node table needs {} entries (at most 2)", image.nodes.size())),
            std::string::npos)
      << nodes;
}

}  // namespace
}  // namespace lancer::fx

namespace lancer::fx {
namespace {

// ---- The treelet layout (layoutBvhTreelets) --------------------------------------------------
// The interior nodes reachable from `ref`, each with the block of its parent.
void collectInterior(const BvhImage& image, const BvhRef& ref, std::vector<uint32_t>& out) {
  if (ref.leaf) return;
  out.push_back(ref.first);
  for (const BvhRef& child : image.nodes[ref.first].child) collectInterior(image, child, out);
}

class GoldenBvhTreelets : public ::testing::TestWithParam<uint32_t> {};

// Every ray walks the same path to the same hit: the same tests, the same
// leaves (index-list entries) in the same order, the interior nodes mapped one
// to one; every node reachable once, in the node table's blocks, each block
// at most its size; the triangles in leaf order.
TEST_P(GoldenBvhTreelets, EveryRayWalksTheSameTreeToTheSameHit) {
  const uint32_t blockNodes = GetParam();
  static const std::vector<QTriangle> tris = quantizeScene(loadScene(test::kBunny));
  const BvhImage plain = buildBvhImage(tris, 4);
  BvhImage laid = plain;
  layoutBvhTreelets(laid, blockNodes);
  EXPECT_EQ(laid.treeletNodes, blockNodes);
  EXPECT_EQ(laid.nodes.size(), plain.nodes.size() + laid.paddingNodes);
  EXPECT_GE(laid.treelets, (plain.nodes.size() + blockNodes - 1) / blockNodes);
  EXPECT_EQ(laid.root.first, 0u) << "the root is node 0";
  for (size_t i = 0; i < laid.indices.size(); ++i) {
    ASSERT_EQ(laid.indices[i], i);
    ASSERT_EQ(laid.triangles[i], plain.triangles[plain.indices[i]]) << "leaf order";
  }
  std::vector<uint32_t> reachable;
  collectInterior(laid, laid.root, reachable);
  ASSERT_EQ(reachable.size(), plain.nodes.size());
  std::sort(reachable.begin(), reachable.end());
  EXPECT_EQ(std::adjacent_find(reachable.begin(), reachable.end()), reachable.end()) << "each node once";
  std::map<uint32_t, uint32_t> perBlock;
  for (uint32_t n : reachable) ++perBlock[laid.blockOf(n)];
  for (const auto& [block, count] : perBlock) EXPECT_LE(count, blockNodes) << "block " << block;
  EXPECT_EQ(reachable.size() + laid.paddingNodes, laid.nodes.size());

  std::mt19937_64 rng{blockNodes};
  std::map<uint32_t, uint32_t> mapped;  // plain node -> laid node, as the walks meet them
  for (uint32_t i = 0; i < 600; ++i) {
    QRay ray = randomLatticeRay(rng, i);
    ray.anyHit = i % 3 == 0;
    const TraversalTrace a = traverseBvh(plain, ray), b = traverseBvh(laid, ray);
    ASSERT_EQ(a.hit, b.hit) << "ray " << i;
    ASSERT_EQ(a.tests, b.tests) << "ray " << i;
    ASSERT_EQ(a.visits.size(), b.visits.size()) << "ray " << i;
    for (size_t k = 0; k < a.visits.size(); ++k) {
      const bool leaf = (a.visits[k] & kBvhLeafVisit) != 0;
      ASSERT_EQ(leaf, (b.visits[k] & kBvhLeafVisit) != 0);
      if (leaf) {
        ASSERT_EQ(a.visits[k], b.visits[k]) << "ray " << i << " leaf " << k;
      } else {
        const auto [it, fresh] = mapped.try_emplace(a.visits[k], b.visits[k]);
        ASSERT_EQ(it->second, b.visits[k]) << "ray " << i << ": node " << a.visits[k] << " maps to one node";
      }
    }
  }
}
INSTANTIATE_TEST_SUITE_P(BlockSizes, GoldenBvhTreelets, ::testing::Values(1u, 2u, 16u, 256u, 4096u));

// A walk crosses into another block at each interior node of another block
// than the one it is in: with one node a block, at every interior node but
// the root; with one block for the whole tree, never; each crossing carries
// at least the state of an empty stack.
TEST(GoldenBvhTreelets, CrossingsAreTheInteriorNodesEnteredInAnotherBlock) {
  const std::vector<QTriangle> tris = quantizeScene(makeCornellBox());
  const BvhImage plain = buildBvhImage(tris, 1);
  BvhImage single = plain, whole = plain;
  layoutBvhTreelets(single, 1);
  layoutBvhTreelets(whole, std::bit_ceil(uint32_t(plain.nodes.size())));
  std::mt19937_64 rng{5};
  TreeletCrossings all;
  for (uint32_t i = 0; i < 300; ++i) {
    const QRay ray = randomLatticeRay(rng, i);
    EXPECT_EQ(bvhTreeletCrossings(plain, ray).rays, 0u) << "no layout, nothing counted";
    EXPECT_EQ(bvhTreeletCrossings(whole, ray).crossings, 0u);
    const TraversalTrace trace = traverseBvh(single, ray);
    const uint64_t interior = uint64_t(std::count_if(trace.visits.begin(), trace.visits.end(),
                                                     [](uint32_t v) { return (v & kBvhLeafVisit) == 0; }));
    const TreeletCrossings c = bvhTreeletCrossings(single, ray);
    ASSERT_EQ(c.rays, 1u);
    ASSERT_EQ(c.crossings, interior > 0 ? interior - 1 : 0) << "ray " << i;
    ASSERT_GE(c.stateBits, c.crossings * uint64_t(bvhSuspendedBits(0)));
    all += c;
  }
  EXPECT_GT(all.crossings, 300u);
  EXPECT_GT(all.stateBits, all.crossings * uint64_t(bvhSuspendedBits(0))) << "some crossings with a stack";
}

// The BVH's walk for test::walkBlockByBlock.
struct BvhWalkOps {
  using Image = BvhImage;
  using Walk = BvhWalk;
  static constexpr int window = kBvhSuspendEntries;
  static Walk start(const Image& image) { return startBvhWalk(image); }
  static void resume(const Image& image, const QRay& ray, Walk& walk, uint32_t block) {
    continueBvhWalk(image, ray, walk, block);
  }
  static Walk carry(const Walk& walk, const QRay& ray) { return bvhWalkOf(bvhWalkValues(walk), ray.id); }
  static TraversalTrace traverse(const Image& image, const QRay& ray) { return traverseBvh(image, ray); }
  static TreeletCrossings crossings(const Image& image, const QRay& ray) { return bvhTreeletCrossings(image, ray); }
};
uint64_t walkBlockByBlock(const BvhImage& image, std::span<const QRay> rays) {
  return test::walkBlockByBlock<BvhWalkOps>(image, rays);
}

TEST(GoldenBvhTreelets, SuspendedWalksResumedBlockByBlockTakeTheUnbrokenWalk) {
  static const std::vector<QTriangle> tris = quantizeScene(loadScene(test::kBunny));
  for (const uint32_t blockNodes : {1u, 16u, 256u}) {
    BvhImage image = buildBvhImage(tris, 4);
    layoutBvhTreelets(image, blockNodes);
    const std::vector<QRay> rays = test::treeletRays(blockNodes, 400);
    const uint64_t suspensions = test::checkBlockByBlock<BvhWalkOps>(image, rays);
    if (blockNodes == 1) {
      EXPECT_GT(suspensions, rays.size());
    }
  }
}

// A crossing with more entries on the stack than the window is not a
// suspension: the walk goes on into the other block. The chain's walk enters
// interior node i (each its own block) with i entries on its stack.
TEST(GoldenBvhTreelets, ACrossingWithAStackDeeperThanTheWindowGoesOn) {
  constexpr int kLevels = 20;
  BvhImage image = test::bvhChainImage(kLevels);
  image.treeletNodes = 1;
  const std::vector<QRay> rays = {QRay{.id = 0, .org = {1, 2, 3}, .dir = {5, 7, 11}}};
  const TreeletCrossings c = bvhTreeletCrossings(image, rays[0]);
  EXPECT_EQ(c.crossings, uint64_t(kLevels - 2));
  EXPECT_EQ(c.suspensions, uint64_t(kBvhSuspendEntries));
  EXPECT_EQ(walkBlockByBlock(image, rays), uint64_t(kBvhSuspendEntries));
}

TEST(GoldenBvhTreelets, TheBudgetIsAtLeastOneNodeAndBlocksArePowersOfTwo) {
  const std::vector<QTriangle> tris = quantizeScene(makeCornellBox());
  BvhImage image = buildBvhImage(tris, 2);
  EXPECT_THROW(layoutBvhTreelets(image, 3), InputError);
  AccelOptions options;
  options.bvhTreeletBytes = int(BvhUnit::kNodeBytes) - 1;
  try {
    BvhUnit::build(tris, options);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), fmt::format("--bvh-treelet-bytes {}: a treelet holds at least one node ({} bytes)",
                                                 BvhUnit::kNodeBytes - 1, BvhUnit::kNodeBytes));
  }
  options.bvhTreeletBytes = int(BvhUnit::kNodeBytes) * 5;  // 5 nodes: blocks of 4
  EXPECT_EQ(BvhUnit::build(tris, options).treeletNodes, 4u);
}

}  // namespace
}  // namespace lancer::fx
