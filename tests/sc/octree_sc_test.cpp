// The SystemC side of rt_octree: the cycle model ("systemc") and the Verilated
// RTL in SystemC ("rtl-systemc") against the golden octree walk
// (fx::traverseOctree), against the timing the micro-architecture prescribes
// (docs/octree-unit.md), against each other cycle for cycle, and against the
// C++ Verilated device ("rtl") when the build has them.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "driver/devices.h"
#include "support/unit_devices.h"
#include "golden/octree.h"
#include "scene/scene.h"
#include "support/octree_cases.h"
#include "trav_sc_fixture.h"

namespace lancer {
namespace {

using Impl = SystemCOctreeDevice::Impl;
using fx::kDirMax;
using fx::kPosBits;
using fx::QRay;
using fx::QTriangle;
using test::expectSameStats;
using test::optionsText;

// ---- Stimulus: the unit's shared hard cases (tests/support/octree_cases.h) ----------

using test::OctreeCase;
using test::QuantizedScene;

QuantizedScene bunnyCamera(int width, int height) {
  static const Scene scene = loadScene(std::string(LANCER_DATA_DIR) + "/scenes/bunny.obj");
  return test::quantizedCamera(scene, width, height);
}

fx::OctreeImage bunnyImage(const QuantizedScene& q) {
  return fx::buildOctreeImage(q.triangles, fx::defaultOctreeDepth(q.triangles.size()), fx::kDefaultOctreeLeafSize);
}

TraversalRunOptions roughOptions(uint64_t seed, int raysInFlight = 0) {
  return test::roughOctreeOptions(seed, raysInFlight);
}

std::string describe(const QRay& r) { return test::describeRay(r); }
std::string describe(const fx::TraversalTrace& t) { return test::describeTrace(t); }

const test::Describe<fx::OctreeImage> kDescribe{
    [](const fx::OctreeImage& image) { return fmt::format("octree depth {}", image.depth); },
    [](const QRay& r) { return describe(r); }, [](const fx::TraversalTrace& t) { return describe(t); }};

// Runs golden and `device`, expects identical traces and golden's counters
// (node reads exactly: no prefetch), and step-ready cycles while nodes are stepped.
TraversalRunStats expectSameTraces(OctreeDevice& device, const fx::OctreeImage& image, const std::vector<QRay>& rays,
                                   const TraversalRunOptions& options, const std::string& what) {
  GoldenOctreeDevice golden;
  const auto [g, r] = test::expectGoldenTraces<fx::OctreeImage>(golden, device, image, rays, options, what, kDescribe);
  EXPECT_EQ(r.nodeReads, g.nodeReads) << what;
  EXPECT_LE(r.stepReadyCycles, r.cycles + 1) << what;
  if (r.steps > 0) {
    EXPECT_GT(r.stepReadyCycles, 0u) << what;
  }
  return r;
}

// ---- Each implementation against the golden model -------------------------------------

class ScOctree : public test::ScTraversalTest<SystemCOctreeDevice> {};

INSTANTIATE_TEST_SUITE_P(Impl, ScOctree, ::testing::Values(Impl::Model, Impl::Rtl), test::implName<Impl>);

TEST_P(ScOctree, MatchesGoldenOnBunnyCameraRays) {
  const QuantizedScene q = bunnyCamera(32, 32);
  const fx::OctreeImage image = bunnyImage(q);
  SystemCOctreeDevice device(GetParam());
  expectSameTraces(device, image, q.rays, roughOptions(1), "bunny 32x32, rough");
}

TEST_P(ScOctree, MatchesGoldenOnHardCasesWithOneSlotAndAllSlots) {
  SystemCOctreeDevice device(GetParam());
  uint64_t seed = 20;
  for (const OctreeCase& c : test::octreeHardCases()) {
    SCOPED_TRACE(c.name);
    expectSameTraces(device, c.image, c.rays, roughOptions(++seed), c.name + ", all slots");
    expectSameTraces(device, c.image, c.rays, roughOptions(++seed, 1), c.name + ", one slot");
  }
}

TEST_P(ScOctree, MatchesGoldenWithoutBackpressure) {
  const QuantizedScene q = bunnyCamera(10, 10);
  const fx::OctreeImage image = bunnyImage(q);
  SystemCOctreeDevice device(GetParam());
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

TEST_P(ScOctree, RepeatedRunsAreIndependentAndReproducible) {
  const QuantizedScene q = bunnyCamera(6, 6);
  test::expectRepeatableRuns<SystemCOctreeDevice>(GetParam(), bunnyImage(q), q.rays, roughOptions(3), roughOptions(4));
}

TEST_P(ScOctree, EmptyRunAndInvalidOptions) {
  SystemCOctreeDevice device(GetParam());
  const fx::OctreeImage image = fx::buildOctreeImage({}, 1, 1);
  test::expectEmptyRun<fx::OctreeImage>(device, image);
  test::expectInvalidOptionsRejected<fx::OctreeImage>(device, image);
  // Still usable afterwards.
  const std::vector<QRay> one{QRay{0, {0, 0, 0}, {kDirMax, 0, 0}}};
  expectSameTraces(device, image, one, {}, "after errors");
}

// ---- The timing the micro-architecture prescribes (docs/octree-unit.md) ---------------

// One ray, latency L, nothing random: the cycle count follows from the state
// machine: accept in 0, ENTER from e = 1 + OCTREE_SETUP_LATENCY; per node entered one visit-grant cycle;
// an interior node then GROUP_REQ, the request on the port, L, DESCEND; ...
uint64_t oneRayCycles(OctreeDevice& device, const fx::OctreeImage& image, const QRay& ray, int latency,
                      fx::TraversalTrace* trace = nullptr) {
  TraversalRunOptions o;
  o.memLatency = latency;
  std::vector<fx::TraversalTrace> traces;
  const TraversalRunStats s = device.run(image, std::vector<QRay>{ray}, traces, o);
  if (trace) *trace = traces.at(0);
  return s.cycles;
}

TEST_P(ScOctree, OneRayTimingFollowsTheStateMachine) {
  SystemCOctreeDevice device(GetParam());
  const int64_t side = int64_t(1) << kPosBits;
  const uint64_t e = 1 + fx::kOctreeSetupLatency;  // the slot leaves SETUP
  // A ray that misses the root: accepted in 0, DONE in e (no node), result
  // pushed at the end of e, on the port in e + 1 and taken there: e + 2 cycles.
  {
    const fx::OctreeImage image = fx::buildOctreeImage({}, 1, 1);
    // Leaves through the corner edge it starts on: t0 = 0 on x (entering), t1 = 0 on y (mirrored, leaving).
    const QRay miss{0, {0, 0, side / 2}, {kDirMax, -kDirMax / 2, 0}};
    fx::TraversalTrace t;
    EXPECT_EQ(oneRayCycles(device, image, miss, 20, &t), e + 2) << "root missed";
    EXPECT_TRUE(t.visits.empty());
  }
  // An empty root leaf: ENTER e (visit grant), CHECK e + 1 (no hit: a lane's
  // grant), the advance at depth 0 in e + 2 -> DONE), DONE e + 3 (done grant),
  // result on the port in e + 4: e + 5 cycles.
  {
    const fx::OctreeImage image = fx::buildOctreeImage({}, 1, 1);
    const QRay ray{0, {side / 2, side / 2, side / 2}, {kDirMax, 0, 0}};
    fx::TraversalTrace t;
    EXPECT_EQ(oneRayCycles(device, image, ray, 20, &t), e + 5) << "empty root leaf";
    EXPECT_EQ(t.visits.size(), 1u);
  }
  // Two empty levels: the root interior, its children empty leaves. A ray along
  // x through the lower half on y and z enters the root, then children 0 and 4
  // (mirrored numbering: x lower, then x upper). Cycles per the state machine,
  // with L the latency: root ENTER e, GROUP_REQ e+1, request on the port e+2,
  // response in e+2+L, DESCEND e+3+L, child ENTER e+4+L, CHECK e+5+L (a
  // lane's grant), the advance in e+6+L (sibling, group valid) -> ENTER
  // e+7+L, CHECK e+8+L, the advance in e+9+L (pop to depth 0 -> DONE), DONE
  // e+10+L, result taken in e+11+L: e + 12 + L cycles; an interior node costs
  // L + 4, an advance 2.
  {
    std::vector<QTriangle> tris;
    for (int i = 0; i < 20; ++i) {  // in the upper y half: the root splits, its lower-y children stay empty
      QTriangle t{uint32_t(i), {}};
      t.v[0] = {side / 8 + i, side - 10, side - 10};
      t.v[1] = {side / 8 + i + 1, side - 10, side - 9};
      t.v[2] = {side / 8 + i, side - 9, side - 10};
      tris.push_back(t);
    }
    const fx::OctreeImage image = fx::buildOctreeImage(tris, 1, 1);
    ASSERT_FALSE(image.nodes[0].leaf);
    const QRay ray{0, {0, side / 4, side / 4}, {kDirMax, 0, 0}};
    for (int latency : {1, 5, 20}) {
      fx::TraversalTrace t;
      const uint64_t cycles = oneRayCycles(device, image, ray, latency, &t);
      ASSERT_EQ(t.visits.size(), 3u) << describe(t);
      ASSERT_TRUE(image.nodes[t.visits[1]].leaf && image.nodes[t.visits[1]].count == 0) << describe(t);
      ASSERT_TRUE(image.nodes[t.visits[2]].leaf && image.nodes[t.visits[2]].count == 0) << describe(t);
      EXPECT_EQ(cycles, e + 12 + uint64_t(latency)) << "latency " << latency;
    }
  }
}

// ---- Cycle accuracy ---------------------------------------------------------------------

std::vector<TraversalRunOptions> timingSettings() { return test::timingSettings(roughOptions, 31, 33, 34); }

std::vector<OctreeCase> cycleCases() {
  const QuantizedScene q = bunnyCamera(16, 16);
  std::vector<OctreeCase> cases{{"bunny 16x16", bunnyImage(q), q.rays}};
  for (OctreeCase& c : test::octreeHardCases()) cases.push_back(std::move(c));
  return cases;
}

TEST(ScOctreeCycleAccuracy, ModelMatchesVerilatedRtlCycleForCycle) {
  test::expectModelMatchesRtlCycleForCycle<SystemCOctreeDevice>(cycleCases(), timingSettings());
}

TEST(ScOctreeCycleAccuracy, StatsEqualTheCxxVerilatedDevice) {
  const std::vector<TraversalRunOptions> settings = timingSettings();
  test::expectStatsEqualTheCxxVerilatedDevice<fx::OctreeUnit, SystemCOctreeDevice>(
      cycleCases(), {settings[0], settings[2], settings[4]}, {Impl::Model});
}

// ---- The device in the process ------------------------------------------------------------

TEST(ScOctreeDevice, NamesAndFactory) {
  test::expectNamesAndFactory<fx::OctreeUnit, SystemCOctreeDevice>(LANCER_OCTREE_RAYS_IN_FLIGHT);
}

TEST(ScOctreeDevice, SharesTheKernelWithTheGridUnit) {
  // Any SystemC system may run first; all are elaborated together.
  const QuantizedScene q = bunnyCamera(4, 4);
  const fx::OctreeImage octree = bunnyImage(q);
  const fx::GridImage grid = fx::buildGridImage(q.triangles, {8, 8, 8});
  for (int round = 0; round < 2; ++round) {
    std::vector<fx::TraversalTrace> want, got;
    GoldenGridDevice().run(grid, q.rays, want);
    SystemCGridDevice().run(grid, q.rays, got, roughOptions(40 + round));
    EXPECT_EQ(got, want);
    SystemCOctreeDevice device;
    expectSameTraces(device, octree, q.rays, roughOptions(50 + round), "interleaved");
  }
}

TEST(ScOctreeDevice, WaveformOfTheRtlOnRequest) {
  const QuantizedScene q = bunnyCamera(3, 3);
  const fx::OctreeImage image = bunnyImage(q);
  test::expectRtlWave<SystemCOctreeDevice>("rt_octree_sc_wave.fst", roughOptions(60),
                          [&](SystemCOctreeDevice& rtl, const TraversalRunOptions& o) {
                            expectSameTraces(rtl, image, q.rays, o, "with waves");
                          });
}

}  // namespace
}  // namespace lancer
