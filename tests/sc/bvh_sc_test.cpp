// The SystemC side of rt_bvh: the cycle model ("systemc") and the Verilated
// RTL in SystemC ("rtl-systemc") against the golden BVH walk
// (fx::traverseBvh), against the timing the micro-architecture prescribes
// (docs/bvh-unit.md), against each other cycle for cycle, and against the
// C++ Verilated device ("rtl") when the build has them.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "driver/devices.h"
#include "golden/bvh.h"
#include "scene/scene.h"
#include "support/bvh_cases.h"
#include "support/unit_devices.h"
#include "trav_sc_fixture.h"

namespace lancer {
namespace {

using Impl = SystemCBvhDevice::Impl;
using fx::kDirMax;
using fx::QRay;
using test::expectSameStats;
using test::optionsText;

// ---- Stimulus: the unit's shared hard cases (tests/support/bvh_cases.h) ----------

using test::BvhCase;
using test::QuantizedScene;

QuantizedScene bunnyCamera(int width, int height) {
  static const Scene scene = loadScene(std::string(LANCER_DATA_DIR) + "/scenes/bunny.obj");
  return test::quantizedCamera(scene, width, height);
}

fx::BvhImage bunnyImage(const QuantizedScene& q) { return fx::buildBvhImage(q.triangles, fx::kDefaultBvhLeafSize); }

TraversalRunOptions roughOptions(uint64_t seed, int raysInFlight = 0) {
  return test::roughTraversalOptions(seed, raysInFlight);
}

const test::Describe<fx::BvhImage> kDescribe{
    [](const fx::BvhImage& image) { return fmt::format("bvh depth {}", image.depth); },
    [](const QRay& r) { return test::describeBvhRay(r); },
    [](const fx::TraversalTrace& t) { return test::describeBvhTrace(t); }};

// Runs golden and `device`, expects identical traces and golden's counters
// (node reads exactly), and step-ready cycles while nodes are stepped.
TraversalRunStats expectSameTraces(BvhDevice& device, const fx::BvhImage& image, const std::vector<QRay>& rays,
                                   const TraversalRunOptions& options, const std::string& what) {
  GoldenBvhDevice golden;
  const auto [g, r] = test::expectGoldenTraces<fx::BvhImage>(golden, device, image, rays, options, what, kDescribe);
  EXPECT_EQ(r.nodeReads, g.nodeReads) << what;
  EXPECT_LE(r.stepReadyCycles, r.cycles + 1) << what;
  if (r.steps > 0) {
    EXPECT_GT(r.stepReadyCycles, 0u) << what;
  }
  return r;
}

// ---- Each implementation against the golden model -------------------------------------

class ScBvh : public test::ScTraversalTest<SystemCBvhDevice> {};

INSTANTIATE_TEST_SUITE_P(Impl, ScBvh, ::testing::Values(Impl::Model, Impl::Rtl), test::implName<Impl>);

TEST_P(ScBvh, MatchesGoldenOnBunnyCameraRays) {
  const QuantizedScene q = bunnyCamera(32, 32);
  SystemCBvhDevice device(GetParam());
  expectSameTraces(device, bunnyImage(q), q.rays, roughOptions(1), "bunny 32x32, rough");
}

TEST_P(ScBvh, MatchesGoldenOnHardCasesWithOneSlotAndAllSlots) {
  SystemCBvhDevice device(GetParam());
  uint64_t seed = 20;
  for (const BvhCase& c : test::bvhHardCases()) {
    SCOPED_TRACE(c.name);
    expectSameTraces(device, c.image, c.rays, roughOptions(++seed), c.name + ", all slots");
    expectSameTraces(device, c.image, c.rays, roughOptions(++seed, 1), c.name + ", one slot");
  }
}

TEST_P(ScBvh, MatchesGoldenWithoutBackpressure) {
  const QuantizedScene q = bunnyCamera(10, 10);
  const fx::BvhImage image = bunnyImage(q);
  SystemCBvhDevice device(GetParam());
  TraversalRunOptions fast;  // no jitter, no stalls, latency 1
  fast.memLatency = 1;
  expectSameTraces(device, image, q.rays, fast, "latency 1, no backpressure");
  expectSameTraces(device, image, q.rays, {}, "latency 20, no backpressure");
  TraversalRunOptions slow = roughOptions(9, 3);
  slow.memLatency = 60;
  slow.memLatencyJitter = 60;
  slow.stream.outputStallProbability = 0.7;
  expectSameTraces(device, image, q.rays, slow, "latency 60 + jitter 60, stalls 0.7, 3 slots");
}

TEST_P(ScBvh, RepeatedRunsAreIndependentAndReproducible) {
  const QuantizedScene q = bunnyCamera(6, 6);
  test::expectRepeatableRuns<SystemCBvhDevice>(GetParam(), bunnyImage(q), q.rays, roughOptions(3), roughOptions(4));
}

TEST_P(ScBvh, EmptyRunAndInvalidOptions) {
  SystemCBvhDevice device(GetParam());
  const fx::BvhImage image = fx::buildBvhImage({}, 4);
  test::expectEmptyRun<fx::BvhImage>(device, image);
  test::expectInvalidOptionsRejected<fx::BvhImage>(device, image);
  // Still usable afterwards.
  const std::vector<QRay> one{QRay{0, {0, 0, 0}, {kDirMax, 0, 0}}};
  expectSameTraces(device, image, one, {}, "after errors");
}

// ---- The timing the micro-architecture prescribes (docs/bvh-unit.md) ---------------

// One ray through a root whose two children are empty leaves spanning the
// lattice, from inside both (entries 0: child 0 first, child 1 pushed):
// accept in 0, ENTER root e = 1 + BVH_SETUP_LATENCY, NODE_REQ e+1, the request
// e+2, the response e+2+L, the box answer a = e+2+L+BVH_BOX_LATENCY, ENTER a+1,
// POP a+2 (pop grant), the pop a+3, ENTER a+4, POP a+5, the pop a+6 (DONE),
// DONE a+7, result taken a+8: e + 11 + BVH_BOX_LATENCY + L cycles.
TEST_P(ScBvh, OneRayTimingFollowsTheStateMachine) {
  SystemCBvhDevice device(GetParam());
  fx::BvhImage image;
  image.leafSize = 1;
  const int shift = fx::bvhShiftFor(int64_t(1) << fx::kPosBits);
  fx::BvhNode node;
  node.shift = {shift, shift, shift};
  for (int c = 0; c < fx::kBvhWidth; ++c) node.hi[size_t(c)] = {fx::kBvhPlaneMax, fx::kBvhPlaneMax, fx::kBvhPlaneMax};
  node.child[0] = node.child[1] = fx::BvhRef{true, 0, 0};
  image.nodes.push_back(node);
  image.root = fx::BvhRef{false, 0, 0};
  image.depth = 2;
  const uint64_t e = 1 + fx::kBvhSetupLatency;
  for (int latency : {1, 5, 20}) {
    TraversalRunOptions o;
    o.memLatency = latency;
    std::vector<fx::TraversalTrace> traces;
    const TraversalRunStats s = device.run(image, std::vector<QRay>{QRay{0, {5, 5, 5}, {kDirMax, 3, 7}}}, traces, o);
    ASSERT_EQ(traces.at(0).visits.size(), 3u);
    EXPECT_EQ(s.cycles, e + 11 + uint64_t(fx::kBvhBoxLatency + latency)) << "latency " << latency;
  }
  // An empty root leaf: ENTER e, POP e+1 (grant), the pop e+2 (DONE), DONE
  // e+3, the result taken e+4: e + 5 cycles.
  std::vector<fx::TraversalTrace> traces;
  const TraversalRunStats s =
      device.run(fx::buildBvhImage({}, 4), std::vector<QRay>{QRay{0, {5, 5, 5}, {kDirMax, 3, 7}}}, traces, {});
  EXPECT_EQ(s.cycles, e + 5) << "empty root leaf";
}

// ---- Cycle accuracy ---------------------------------------------------------------------

std::vector<TraversalRunOptions> timingSettings() { return test::timingSettings(roughOptions, 31, 33, 34); }

std::vector<BvhCase> cycleCases() {
  const QuantizedScene q = bunnyCamera(16, 16);
  std::vector<BvhCase> cases{{"bunny 16x16", bunnyImage(q), q.rays}};
  for (BvhCase& c : test::bvhHardCases()) cases.push_back(std::move(c));
  return cases;
}

TEST(ScBvhCycleAccuracy, ModelMatchesVerilatedRtlCycleForCycle) {
  test::expectModelMatchesRtlCycleForCycle<SystemCBvhDevice>(cycleCases(), timingSettings());
}

TEST(ScBvhCycleAccuracy, StatsEqualTheCxxVerilatedDevice) {
  const std::vector<TraversalRunOptions> settings = timingSettings();
  test::expectStatsEqualTheCxxVerilatedDevice<fx::BvhUnit, SystemCBvhDevice>(
      cycleCases(), {settings[0], settings[2], settings[4]}, {Impl::Model});
}

// ---- The device in the process ------------------------------------------------------------

TEST(ScBvhDevice, NamesAndFactory) {
  test::expectNamesAndFactory<fx::BvhUnit, SystemCBvhDevice>(LANCER_BVH_RAYS_IN_FLIGHT);
}

TEST(ScBvhDevice, SharesTheKernelWithTheOctreeUnit) {
  const QuantizedScene q = bunnyCamera(4, 4);
  const fx::BvhImage bvh = bunnyImage(q);
  const fx::OctreeImage octree =
      fx::buildOctreeImage(q.triangles, fx::defaultOctreeDepth(q.triangles.size()), fx::kDefaultOctreeLeafSize);
  for (int round = 0; round < 2; ++round) {
    std::vector<fx::TraversalTrace> want, got;
    GoldenOctreeDevice().run(octree, q.rays, want);
    SystemCOctreeDevice().run(octree, q.rays, got, roughOptions(40 + round));
    EXPECT_EQ(got, want);
    SystemCBvhDevice device;
    expectSameTraces(device, bvh, q.rays, roughOptions(50 + round), "interleaved");
  }
}

TEST(ScBvhDevice, WaveformOfTheRtlOnRequest) {
  const QuantizedScene q = bunnyCamera(3, 3);
  const fx::BvhImage image = bunnyImage(q);
  test::expectRtlWave<SystemCBvhDevice>("rt_bvh_sc_wave.fst", roughOptions(60),
                                        [&](SystemCBvhDevice& rtl, const TraversalRunOptions& o) {
                                          expectSameTraces(rtl, image, q.rays, o, "with waves");
                                        });
}

}  // namespace
}  // namespace lancer
