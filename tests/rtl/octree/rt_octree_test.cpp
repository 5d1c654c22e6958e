// The Verilated rt_octree against the golden octree model (fx::traverseOctree):
// for every ray the same nodes in the same order, the same number of tests and
// the same closest hit, bit for bit, under memory latency jitter, output
// backpressure and input bubbles; the same memory reads as the golden device
// counts them (one child group per interior node entered, one per refill).
#include <gtest/gtest.h>

#include <random>

#include <fmt/format.h>

#include "common/error.h"
#include "driver/devices.h"
#include "driver/traversal_device.h"
#include "support/unit_devices.h"
#include "golden/isect.h"
#include "scene/scene.h"
#include "support/octree_cases.h"
#include "octree/too_deep_image.h"
#include "trav_test_support.h"

namespace lancer::rtltest {
namespace {

using fx::OctreeImage;
using test::OctreeCase;

VerilatorOctreeDevice& rtl() { return sharedDevice<VerilatorOctreeDevice>(); }

// The RTL (`device`) beside the golden octree (compareWithGolden), and the
// node reads, which are the same; returns the RTL's stats.
TraversalRunStats expectSameTraces(const OctreeImage& image, const std::vector<QRay>& rays,
                                   const TraversalRunOptions& options, VerilatorOctreeDevice& device = rtl()) {
  const std::string where = fmt::format("octree depth {} ({} nodes)", image.depth, image.nodes.size());
  const auto [g, r] = compareWithGolden<GoldenOctreeDevice>(device, image, rays, options,
                                                            {where, test::describeRay, test::describeTrace});
  EXPECT_EQ(r.nodeReads, g.nodeReads);
  EXPECT_GT(r.cycles, 0u);
  if (g.steps > 0) {
    EXPECT_GT(r.stepReadyCycles, 0u);
    EXPECT_LE(r.stepReadyCycles, r.cycles + 8);
  }
  return r;
}

const OctreeCase& hardCase(const std::string& name) { return test::caseNamed<test::octreeHardCases>(name); }

class RtOctreeHardCases : public ::testing::TestWithParam<std::string> {};

// Every case with all slots under jitter, stalls and bubbles; then one slot.
TEST_P(RtOctreeHardCases, MatchGolden) {
  const OctreeCase& c = hardCase(GetParam());
  const uint64_t seed = std::hash<std::string>{}(c.name) % 1000;
  expectSameTraces(c.image, c.rays, test::roughOctreeOptions(seed));
  // One slot walks the rays one after the other: a third of them keeps it quick.
  const std::vector<QRay> some(c.rays.begin(), c.rays.begin() + std::max<size_t>(1, c.rays.size() / 3));
  expectSameTraces(c.image, some, test::roughOctreeOptions(seed + 1, 1));
}

INSTANTIATE_TEST_SUITE_P(Cases, RtOctreeHardCases, ::testing::ValuesIn(test::caseNames<test::octreeHardCases>()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

const Scene& bunny() {
  static const Scene scene = loadScene(std::string(LANCER_DATA_DIR) + "/scenes/bunny.obj");
  return scene;
}

OctreeImage defaultImage(const std::vector<fx::QTriangle>& triangles) {
  return fx::buildOctreeImage(triangles, fx::defaultOctreeDepth(triangles.size()), fx::kDefaultOctreeLeafSize);
}

TEST(RtOctree, BunnyCameraRays) {
  const test::QuantizedScene q = test::quantizedCamera(bunny(), 40, 40);
  expectSameTraces(defaultImage(q.triangles), q.rays, test::roughOctreeOptions(1));
}

TEST(RtOctree, BunnyRandomRaysAtSeveralDepthsAndLeafSizes) {
  const test::QuantizedScene q = test::quantizedCamera(bunny(), 1, 1);
  std::mt19937_64 rng(2);
  std::uniform_int_distribution<int64_t> pos(0, kPosMax), dir(-kDirMax, kDirMax);
  std::vector<QRay> rays;
  for (uint32_t i = 0; i < 300; ++i) {
    QRay r{i, {pos(rng), pos(rng), pos(rng)}, {dir(rng), dir(rng), dir(rng)}};
    const int k = fx::dominantAxis(r.dir);
    r.dir[k] = r.dir[k] < 0 ? -kDirMax : kDirMax;
    rays.push_back(r);
  }
  for (const auto& [depth, leaf] : {std::pair{1, 8}, {4, 8}, {8, 1}, {fx::kOctreeMaxDepth, 2}}) {
    SCOPED_TRACE(fmt::format("depth {} leaf {}", depth, leaf));
    // A shallow tree tests hundreds of triangles per leaf: fewer rays there.
    const std::vector<QRay> some(rays.begin(), rays.begin() + (depth == 1 ? 40 : 300));
    expectSameTraces(fx::buildOctreeImage(q.triangles, depth, leaf), some, test::roughOctreeOptions(3 + depth));
  }
}

TEST(RtOctree, OneRayInFlightAllSlotsAndNoStalls) {
  const test::QuantizedScene q = test::quantizedCamera(bunny(), 12, 12);
  const OctreeImage image = defaultImage(q.triangles);
  expectSameTraces(image, q.rays, test::roughOctreeOptions(15, 1));
  expectSameTraces(image, q.rays, test::roughOctreeOptions(16, rtl().maxRaysInFlight()));
  TraversalRunOptions fast;  // no jitter, no stalls, latency 1
  fast.memLatency = 1;
  const TraversalRunStats s = expectSameTraces(image, q.rays, fast);
  // Repeated runs on one device give the same cycles.
  std::vector<fx::TraversalTrace> again;
  EXPECT_EQ(rtl().run(image, q.rays, again, fast).cycles, s.cycles);
}

// One ray alone, memory latency L, no stalls: the cycle count follows the
// micro-architecture's timing (docs/octree-unit.md): setup
// 1 + OCTREE_SETUP_LATENCY cycles, an
// interior node L + 4, an empty leaf 3 (its check, then the advance a lane
// granted), plus the result.
TEST(RtOctree, TimingOfOneRayThroughEmptyLeaves) {
  // Two tiny triangles in one corner: the root splits, the ray below crosses
  // empty children of the root only.
  const std::vector<fx::QTriangle> tris{
      fx::QTriangle{0, {{{1, 1, 1}, {3, 1, 1}, {1, 3, 1}}}}, fx::QTriangle{1, {{{2, 2, 2}, {3, 2, 2}, {2, 3, 3}}}}};
  const OctreeImage image = fx::buildOctreeImage(tris, 1, 1);
  ASSERT_EQ(image.nodes.size(), 9u);
  const int64_t half = (kPosMax + 1) / 2;
  // From the upper half on every axis along -x: visits the root, child 7 (empty), child 3 (empty).
  const std::vector<QRay> rays{QRay{0, {half + 5, half + 7, half + 9}, {-kDirMax, 0, 0}}};
  for (int latency : {1, 5, 20}) {
    TraversalRunOptions o;
    o.memLatency = latency;
    const TraversalRunStats s = expectSameTraces(image, rays, o);
    // Accepted in cycle 0, ENTER root in e = 1 + OCTREE_SETUP_LATENCY,
    // GROUP_REQ e + 1, the request on the port e + 2, the response e + 2 + L,
    // DESCEND e + 3 + L, ENTER child 7 in e + 4 + L, CHECK e + 5 + L (no hit: a
    // lane's grant), the advance to the sibling in e + 6 + L, ENTER child 3 in
    // e + 7 + L, CHECK e + 8 + L, the advance in e + 9 + L (pop to the root:
    // DONE), DONE e + 10 + L (result FIFO), the result taken in e + 11 + L:
    // e + 12 + L cycles.
    const int enterRoot = 1 + fx::kOctreeSetupLatency;
    EXPECT_EQ(s.cycles, uint64_t(enterRoot + 12 + latency)) << "latency " << latency;
    EXPECT_EQ(s.nodeReads, 1u);
  }
}

TEST(RtOctree, RejectsBadConfigurations) {
  const OctreeImage image = fx::buildOctreeImage({}, 1, 8);
  const std::vector<QRay> one{QRay{0, {0, 0, 0}, {kDirMax, 0, 0}}};
  expectRejectsRaysInFlight<OctreeImage>(rtl(), image, one, "LANCER_OCTREE_RAYS_IN_FLIGHT");
  std::vector<fx::TraversalTrace> traces;
  const TraversalRunOptions o;
  EXPECT_THROW(rtl().run(image, std::vector<QRay>{QRay{0, {1, 2, 3}, {0, 0, 0}}}, traces, o), InputError);
  EXPECT_THROW(rtl().run(OctreeImage{}, one, traces, o), InputError);
  // An image deeper than the unit's stack (the descriptor's check, as in every model).
  OctreeImage deep = image;
  deep.depth = fx::kOctreeMaxDepth + 1;
  EXPECT_THROW(rtl().run(deep, one, traces, o), InputError);
  // A corrupt image: an interior node whose children lie outside the node table.
  OctreeImage broken = image;
  broken.nodes[0] = fx::OctreeNode{false, 5, 0};
  try {
    rtl().run(broken, one, traces, o);
    FAIL() << "no runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("outside the node table"), std::string::npos) << e.what();
  }
  // The device still works afterwards.
  expectSameTraces(image, one, o);
  // The factory knows it.
  EXPECT_EQ(makeTraversalDevice<fx::OctreeUnit>("rtl")->name(), "rtl");
  EXPECT_EQ(makeTraversalDevice<fx::OctreeUnit>("rtl")->maxRaysInFlight(), LANCER_OCTREE_RAYS_IN_FLIGHT);
}

// Runs `device` on the too-deep image: it must throw, naming rt_octree's assertion.
void expectAssertionFails(VerilatorOctreeDevice& device) {
  std::vector<fx::TraversalTrace> traces;
  try {
    device.run(tooDeepOctreeImage(), kTooDeepDiagonalRay, traces, TraversalRunOptions{});
    ADD_FAILURE() << "no assertion fired";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("assertion of rt_octree failed"), std::string::npos) << e.what();
  }
}

// The SVA checks are compiled in and turn into exceptions.
TEST(RtOctree, AssertionsAreLive) {
  expectAssertionFails(rtl());
  // The next run resets the unit and works.
  const OctreeCase& c = hardCase("octants");
  expectSameTraces(c.image, c.rays, test::roughOctreeOptions(19));
}

// Verilator reports a failed assertion to the thread's current
// VerilatedContext, the last one made or selected: each device selects its
// own in every run. The older of two devices alive trips the assertion and
// reports it itself (without the selection it would go to the newer one's
// context, and the older device's run would end without an error); the newer
// one is not disturbed, and the older one works again afterwards.
TEST(RtOctree, EachDeviceReportsItsOwnAssertions) {
  VerilatorOctreeDevice older;
  VerilatorOctreeDevice newer;
  const OctreeCase& c = hardCase("octants");
  expectSameTraces(c.image, c.rays, test::roughOctreeOptions(20), newer);
  expectAssertionFails(older);
  expectSameTraces(c.image, c.rays, test::roughOctreeOptions(21), newer);
  expectSameTraces(c.image, c.rays, test::roughOctreeOptions(22), older);
  expectAssertionFails(newer);
  expectSameTraces(c.image, c.rays, test::roughOctreeOptions(23), older);
}

TEST(RtOctree, WritesAnFstWaveformWhenAsked) {
  const OctreeCase& c = hardCase("octants");
  const std::vector<QRay> rays(c.rays.begin(), c.rays.begin() + 8);
  TraversalRunOptions o = test::roughOctreeOptions(18);
  o.stream.wavePath = wavePath("rt_octree_wave");
  expectSameTraces(c.image, rays, o);
  expectWaveform(o.stream.wavePath);
  // The next run writes no waveform and still matches.
  o.stream.wavePath.clear();
  expectSameTraces(c.image, rays, o);
}

// Performance sweep, not a check (docs/octree-unit.md has the table). Run with
//   build/tests/rtl/rtl_octree_tests --gtest_also_run_disabled_tests --gtest_filter='*Sweep*'
// LANCER_OCTREE_SWEEP_SIZE sets the image side (default 256).
TEST(RtOctree, DISABLED_Sweep) {
  const int side = sweepSide("LANCER_OCTREE_SWEEP_SIZE");
  const test::QuantizedScene q = test::quantizedCamera(bunny(), side, side);
  const OctreeImage image = defaultImage(q.triangles);
  fmt::print("bunny {} tris, octree depth {} (max {}), leaf {}, {} nodes, {} camera rays ({}x{})\n",
             q.triangles.size(), image.depth, image.maxDepth, image.leafSize, image.nodes.size(), q.rays.size(), side,
             side);
  printSweep<OctreeImage>(rtl(), image, q.rays);
}

}  // namespace
}  // namespace lancer::rtltest
