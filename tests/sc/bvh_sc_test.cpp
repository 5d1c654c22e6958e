// The SystemC side of rt_bvh beyond the shared suite (trav_sc_suite.h, run
// over the unit by trav_sc_units.cpp): the timing the micro-architecture
// prescribes (docs/bvh-unit.md), on the cycle model and the Verilated RTL.
#include <gtest/gtest.h>

#include <vector>

#include "golden/bvh.h"
#include "support/bvh_cases.h"
#include "trav_sc_suite.h"
#include "trav_sc_treelets.h"

namespace lancer {
namespace {

using fx::kDirMax;
using fx::QRay;

class ScBvh : public test::ScTraversalTest<SystemCBvhDevice> {};

INSTANTIATE_TEST_SUITE_P(Impl, ScBvh, ::testing::Values(SystemCImpl::Model, SystemCImpl::Pins, SystemCImpl::Rtl),
                         test::implName<SystemCImpl>);

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

// The treelet schedule on the cycle model (test::checkTreeletRuns): every
// hard case with each node its own treelet block (the most suspensions: the
// chain's walk is deeper than the suspend window): every ray takes its
// unbroken walk, bit for bit, and the units set aside exactly the golden
// walk's suspensions.
TEST(ScBvhTreelets, SuspendedWalksTakeTheUnbrokenWalkThroughTheRayQueues) {
  SystemCBvhDevice device(SystemCImpl::Model);
  mem::RayQueueStats all;
  for (test::BvhCase c : test::bvhHardCases()) {
    c.image.treeletNodes = 1;
    fx::TreeletCrossings expected;
    for (const QRay& ray : c.rays) expected += fx::bvhTreeletCrossings(c.image, ray);
    test::checkTreeletRuns(device, c.name, c.image, c.rays, expected.suspensions, fx::traverseBvh, all);
    if (c.name == "chain") {
      EXPECT_GT(expected.crossings, expected.suspensions) << "the window's limit is met";
    }
  }
  EXPECT_GT(all.suspensions, 1000u);
  EXPECT_GT(all.overflows, 0u);
  EXPECT_GT(all.bytesWritten, 0u);
}

}  // namespace
}  // namespace lancer
