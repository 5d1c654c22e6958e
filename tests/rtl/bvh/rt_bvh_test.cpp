// The Verilated rt_bvh against the golden BVH model (fx::traverseBvh): for
// every ray the same nodes in the same order, the same number of tests and the
// same closest hit, bit for bit, under memory latency jitter, output
// backpressure and input bubbles; the same memory reads as the golden device
// counts them (one node read per interior node entered).
#include <gtest/gtest.h>

#include <random>

#include <fmt/format.h>

#include "common/error.h"
#include "driver/devices.h"
#include "driver/traversal_device.h"
#include "golden/bvh_unit.h"
#include "scene/scene.h"
#include "support/bvh_cases.h"
#include "support/unit_devices.h"
#include "trav_test_support.h"

namespace lancer::rtltest {
namespace {

using fx::BvhImage;
using test::BvhCase;

VerilatorBvhDevice& rtl() { return sharedDevice<VerilatorBvhDevice>(); }

// The RTL (`device`) beside the golden BVH walk (compareWithGolden), and the
// node reads, which are the same; returns the RTL's stats.
TraversalRunStats expectSameTraces(const BvhImage& image, const std::vector<QRay>& rays,
                                   const TraversalRunOptions& options, VerilatorBvhDevice& device = rtl()) {
  const std::string where = fmt::format("bvh depth {} ({} nodes)", image.depth, image.nodes.size());
  const auto [g, r] = compareWithGolden<GoldenBvhDevice>(device, image, rays, options,
                                                         {where, test::describeBvhRay, test::describeBvhTrace});
  EXPECT_EQ(r.nodeReads, g.nodeReads);
  EXPECT_GT(r.cycles, 0u);
  if (g.steps > 0) {
    EXPECT_GT(r.stepReadyCycles, 0u);
    EXPECT_LE(r.stepReadyCycles, r.cycles + 8);
  }
  return r;
}

const BvhCase& hardCase(const std::string& name) { return test::caseNamed<test::bvhHardCases>(name); }

class RtBvhHardCases : public ::testing::TestWithParam<std::string> {};

// Every case with all slots under jitter, stalls and bubbles; then one slot.
TEST_P(RtBvhHardCases, MatchGolden) {
  const BvhCase& c = hardCase(GetParam());
  const uint64_t seed = std::hash<std::string>{}(c.name) % 1000;
  expectSameTraces(c.image, c.rays, test::roughTraversalOptions(seed));
  // One slot walks the rays one after the other: a third of them keeps it quick.
  const std::vector<QRay> some(c.rays.begin(), c.rays.begin() + std::max<size_t>(1, c.rays.size() / 3));
  expectSameTraces(c.image, some, test::roughTraversalOptions(seed + 1, 1));
}

INSTANTIATE_TEST_SUITE_P(Cases, RtBvhHardCases, ::testing::ValuesIn(test::caseNames<test::bvhHardCases>()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

const Scene& bunny() {
  static const Scene scene = loadScene(std::string(LANCER_DATA_DIR) + "/scenes/bunny.obj");
  return scene;
}

BvhImage defaultImage(const std::vector<fx::QTriangle>& triangles) {
  return fx::buildBvhImage(triangles, fx::kDefaultBvhLeafSize);
}

TEST(RtBvh, BunnyCameraRays) {
  const test::QuantizedScene q = test::quantizedCamera(bunny(), 40, 40);
  expectSameTraces(defaultImage(q.triangles), q.rays, test::roughTraversalOptions(1));
}

TEST(RtBvh, BunnyRandomRaysAtSeveralLeafSizes) {
  const test::QuantizedScene q = test::quantizedCamera(bunny(), 1, 1);
  std::mt19937_64 rng(2);
  std::vector<QRay> rays;
  for (uint32_t i = 0; i < 300; ++i) rays.push_back(test::randomLatticeRay(rng, i));
  for (const int leaf : {1, 4, 16, 255}) {
    SCOPED_TRACE(fmt::format("leaf {}", leaf));
    const std::vector<QRay> some(rays.begin(), rays.begin() + (leaf == 255 ? 60 : 300));
    expectSameTraces(fx::buildBvhImage(q.triangles, leaf), some, test::roughTraversalOptions(3 + leaf));
  }
}

TEST(RtBvh, BunnySegmentsAndAnyHit) {
  const test::QuantizedScene q = test::quantizedCamera(bunny(), 12, 12);
  const std::vector<QRay> rays = test::segmentVariants(q.triangles, q.rays, 40);
  expectSameTraces(defaultImage(q.triangles), rays, test::roughTraversalOptions(7));
}

TEST(RtBvh, OneRayInFlightAllSlotsAndNoStalls) {
  const test::QuantizedScene q = test::quantizedCamera(bunny(), 12, 12);
  const BvhImage image = defaultImage(q.triangles);
  expectSameTraces(image, q.rays, test::roughTraversalOptions(15, 1));
  expectSameTraces(image, q.rays, test::roughTraversalOptions(16, rtl().maxRaysInFlight()));
  TraversalRunOptions fast;  // no jitter, no stalls, latency 1
  fast.memLatency = 1;
  const TraversalRunStats s = expectSameTraces(image, q.rays, fast);
  // Repeated runs on one device give the same cycles.
  std::vector<fx::TraversalTrace> again;
  EXPECT_EQ(rtl().run(image, q.rays, again, fast).cycles, s.cycles);
}

// A root whose two children are empty leaves spanning the lattice.
BvhImage twoEmptyLeaves() {
  BvhImage image;
  image.leafSize = 1;
  const int shift = fx::bvhShiftFor(int64_t(1) << fx::kPosBits);
  fx::BvhNode node;
  node.shift = {shift, shift, shift};
  for (int c = 0; c < fx::kBvhWidth; ++c) node.hi[size_t(c)] = {fx::kBvhPlaneMax, fx::kBvhPlaneMax, fx::kBvhPlaneMax};
  node.child[0] = fx::BvhRef{true, 0, 0};
  node.child[1] = fx::BvhRef{true, 0, 0};
  image.nodes.push_back(node);
  image.root = fx::BvhRef{false, 0, 0};
  image.depth = 2;
  image.leaves = 2;
  return image;
}

// One ray alone, memory latency L, no stalls: the cycle count follows the
// micro-architecture's timing (docs/bvh-unit.md, "Timing of one ray").
TEST(RtBvh, TimingOfOneRayThroughTwoEmptyLeaves) {
  const BvhImage image = twoEmptyLeaves();
  // From inside both children (entries 0, a tie: child 0 first, child 1 pushed).
  const std::vector<QRay> rays{QRay{0, {5, 5, 5}, {kDirMax, 3, 7}}};
  for (int latency : {1, 5, 20}) {
    TraversalRunOptions o;
    o.memLatency = latency;
    const TraversalRunStats s = expectSameTraces(image, rays, o);
    // Accepted in cycle 0, ENTER root in e = 1 + BVH_SETUP_LATENCY, NODE_REQ
    // e + 1, the request on the port e + 2, the response e + 2 + L (into
    // u_box), the answer a = e + 2 + L + BVH_BOX_LATENCY (push child 1), ENTER
    // child 0 in a + 1, POP a + 2 (the pop lane's grant), the pop a + 3, ENTER
    // child 1 a + 4, POP a + 5, the pop a + 6 (stack empty: DONE), DONE a + 7
    // (result FIFO), the result taken in a + 8: e + 11 + BVH_BOX_LATENCY + L
    // cycles (e + 15 + L).
    const int enterRoot = 1 + fx::kBvhSetupLatency;
    EXPECT_EQ(s.cycles, uint64_t(enterRoot + 11 + fx::kBvhBoxLatency + latency)) << "latency " << latency;
    EXPECT_EQ(s.nodeReads, 1u);
    EXPECT_EQ(s.steps, 3u);
  }
}

TEST(RtBvh, RejectsBadConfigurations) {
  const BvhImage image = fx::buildBvhImage({}, 4);
  const std::vector<QRay> one{QRay{0, {0, 0, 0}, {kDirMax, 0, 0}}};
  expectRejectsRaysInFlight<BvhImage>(rtl(), image, one, "LANCER_BVH_RAYS_IN_FLIGHT");
  std::vector<fx::TraversalTrace> traces;
  const TraversalRunOptions o;
  // A zero direction.
  EXPECT_THROW(rtl().run(image, std::vector<QRay>{QRay{0, {1, 2, 3}, {0, 0, 0}}}, traces, o), InputError);
  // An image deeper than the unit's stack (the descriptor's check, as in every model).
  EXPECT_THROW(rtl().run(test::bvhChainImage(fx::kBvhMaxLevels + 1), one, traces, o), InputError);
  // An interior root without nodes.
  BvhImage rootless = image;
  rootless.root = fx::BvhRef{false, 0, 0};
  EXPECT_THROW(rtl().run(rootless, one, traces, o), InputError);
  // A corrupt image: an interior child that lies outside the node table.
  BvhImage broken = twoEmptyLeaves();
  broken.nodes[0].child[1] = fx::BvhRef{false, 0, 5};
  try {
    rtl().run(broken, std::vector<QRay>{QRay{0, {5, 5, 5}, {kDirMax, 3, 7}}}, traces, o);
    FAIL() << "no runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("outside the node table"), std::string::npos) << e.what();
  }
  // The device still works afterwards.
  expectSameTraces(image, one, o);
  // The factory knows it.
  EXPECT_EQ(makeTraversalDevice<fx::BvhUnit>("rtl")->name(), "rtl");
  EXPECT_EQ(makeTraversalDevice<fx::BvhUnit>("rtl")->maxRaysInFlight(), LANCER_BVH_RAYS_IN_FLIGHT);
}

// The stack at its limit: a chain of kBvhMaxLevels levels fills it (and
// matches golden, in the hard cases); one level more, with a depth that claims
// to fit (as a corrupt image would), overflows it and trips a_stack_depth.
TEST(RtBvh, StackOverflowTripsItsAssertion) {
  BvhImage deep = test::bvhChainImage(fx::kBvhMaxLevels + 1);
  deep.depth = fx::kBvhMaxLevels;
  std::vector<fx::TraversalTrace> traces;
  try {
    rtl().run(deep, std::vector<QRay>{QRay{0, {5, 5, 5}, {kDirMax, 3, 7}}}, traces, TraversalRunOptions{});
    ADD_FAILURE() << "no assertion fired";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("assertion of rt_bvh failed"), std::string::npos) << e.what();
  }
  // The next run resets the unit and works.
  const BvhCase& c = hardCase("chain");
  expectSameTraces(c.image, c.rays, test::roughTraversalOptions(19));
}

TEST(RtBvh, WritesAnFstWaveformWhenAsked) {
  const BvhCase& c = hardCase("octants");
  const std::vector<QRay> rays(c.rays.begin(), c.rays.begin() + 8);
  TraversalRunOptions o = test::roughTraversalOptions(18);
  o.stream.wavePath = wavePath("rt_bvh_wave");
  expectSameTraces(c.image, rays, o);
  expectWaveform(o.stream.wavePath);
  // The next run writes no waveform and still matches.
  o.stream.wavePath.clear();
  expectSameTraces(c.image, rays, o);
}

// Figures, not a check: the BVH unit and the octree unit on the same bunny
// camera rays, 32 slots, memory latency 20, no jitter or stalls (the defaults
// of TraversalRunOptions). Run with
//   build/tests/rtl/rtl_bvh_tests --gtest_also_run_disabled_tests --gtest_filter='*AgainstTheOctree*'
// LANCER_BVH_SWEEP_SIZE sets the image side (default 256).
TEST(RtBvh, DISABLED_AgainstTheOctree) {
  const int side = sweepSide("LANCER_BVH_SWEEP_SIZE");
  const test::QuantizedScene q = test::quantizedCamera(bunny(), side, side);
  const BvhImage bvh = defaultImage(q.triangles);
  const fx::OctreeImage octree =
      fx::buildOctreeImage(q.triangles, fx::defaultOctreeDepth(q.triangles.size()), fx::kDefaultOctreeLeafSize);
  fmt::print("bunny {} tris, {} camera rays ({}x{}); bvh depth {}, leaf {}, {} interior nodes; octree depth {}\n",
             q.triangles.size(), q.rays.size(), side, side, bvh.depth, bvh.leafSize, bvh.nodes.size(), octree.depth);
  const auto show = [&](const char* unit, const TraversalRunStats& s) {
    const double c = double(s.cycles);
    fmt::print("{:<7} cycles {:>9}  steps {:>8} ({:.2f}/ray)  node reads {:>8} ({:.2f}/ray)  tests {:>8} ({:.2f}/ray)"
               "  isect busy {:.1f}%\n",
               unit, s.cycles, s.steps, double(s.steps) / double(s.rays), s.nodeReads,
               double(s.nodeReads) / double(s.rays), s.isectTests, double(s.isectTests) / double(s.rays),
               100.0 * double(s.isectBusyCycles) / c);
  };
  std::vector<fx::TraversalTrace> traces;
  show("bvh", expectSameTraces(bvh, q.rays, TraversalRunOptions{}));
  show("octree", makeTraversalDevice<fx::OctreeUnit>("rtl")->run(octree, q.rays, traces, TraversalRunOptions{}));
}

// Performance sweep, not a check. Run with
//   build/tests/rtl/rtl_bvh_tests --gtest_also_run_disabled_tests --gtest_filter='*Sweep*'
// LANCER_BVH_SWEEP_SIZE sets the image side (default 256).
TEST(RtBvh, DISABLED_Sweep) {
  const int side = sweepSide("LANCER_BVH_SWEEP_SIZE");
  const test::QuantizedScene q = test::quantizedCamera(bunny(), side, side);
  const BvhImage image = defaultImage(q.triangles);
  fmt::print("bunny {} tris, bvh depth {}, leaf {}, {} nodes, {} camera rays ({}x{})\n", q.triangles.size(),
             image.depth, image.leafSize, image.nodes.size(), q.rays.size(), side, side);
  printSweep<BvhImage>(rtl(), image, q.rays);
}

}  // namespace
}  // namespace lancer::rtltest
