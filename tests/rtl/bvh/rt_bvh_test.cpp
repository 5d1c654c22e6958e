// The Verilated rt_bvh against the golden BVH model (fx::traverseBvh):
// the shared suite (trav_rtl_suite.h: hard cases, the bunny, one slot and all,
// waveforms, the sweep), and the unit's own cases: its timing, its bad
// configurations, its assertions, what only it has.
#include <gtest/gtest.h>


#include <fmt/format.h>

#include "common/error.h"
#include "driver/devices.h"
#include "driver/traversal_device.h"
#include "golden/bvh_unit.h"
#include "scene/scene.h"
#include "support/bvh_cases.h"
#include "support/unit_devices.h"
#include "trav_rtl_suite.h"
#include "trav_rtl_treelets.h"

namespace lancer::rtltest {
namespace {

using fx::BvhImage;
using test::BvhCase;

using Bvh = RtlUnit<fx::BvhUnit>;

TEST(RtBvh, BunnySegmentsAndAnyHit) {
  const test::QuantizedScene q = Bvh::bunny(12, 12);
  const std::vector<QRay> rays = test::segmentVariants(q.triangles, q.rays, 40);
  Bvh::expectSameTraces(Bvh::Traits::image(q.triangles), rays, Bvh::rough(7));
}

// One ray alone, memory latency L, no stalls: the cycle count follows the
// micro-architecture's timing (docs/bvh-unit.md, "Timing of one ray").
TEST(RtBvh, TimingOfOneRayThroughTwoEmptyLeaves) {
  const BvhImage image = test::bvhTwoEmptyLeaves();
  // From inside both children (entries 0, a tie: child 0 first, child 1 pushed).
  const std::vector<QRay> rays{QRay{0, {5, 5, 5}, {kDirMax, 3, 7}}};
  for (int latency : {1, 5, 20}) {
    TraversalRunOptions o;
    o.memLatency = latency;
    const TraversalRunStats s = Bvh::expectSameTraces(image, rays, o);
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

// Its own bad input (the typed suite has the shared cases).
TEST(RtBvh, RejectsBadConfigurations) {
  const BvhImage image = fx::buildBvhImage({}, 4);
  const std::vector<QRay> one{QRay{0, {0, 0, 0}, {kDirMax, 0, 0}}};
  std::vector<fx::TraversalTrace> traces;
  const TraversalRunOptions o;
  // A zero direction.
  EXPECT_THROW(Bvh::rtl().run(image, std::vector<QRay>{QRay{0, {1, 2, 3}, {0, 0, 0}}}, traces, o), InputError);
  // An image deeper than the unit's stack (the descriptor's check, as in every model).
  EXPECT_THROW(Bvh::rtl().run(test::bvhChainImage(fx::kBvhMaxLevels + 1), one, traces, o), InputError);
  // An interior root without nodes.
  BvhImage rootless = image;
  rootless.root = fx::BvhRef{false, 0, 0};
  EXPECT_THROW(Bvh::rtl().run(rootless, one, traces, o), InputError);
}

// The stack at its limit: a chain of kBvhMaxLevels levels fills it (and
// matches golden, in the hard cases); one level more, with a depth that claims
// to fit (as a corrupt image would), overflows it and trips a_stack_depth.
TEST(RtBvh, StackOverflowTripsItsAssertion) {
  BvhImage deep = test::bvhChainImage(fx::kBvhMaxLevels + 1);
  deep.depth = fx::kBvhMaxLevels;
  std::vector<fx::TraversalTrace> traces;
  try {
    Bvh::rtl().run(deep, std::vector<QRay>{QRay{0, {5, 5, 5}, {kDirMax, 3, 7}}}, traces, TraversalRunOptions{});
    ADD_FAILURE() << "no assertion fired";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("assertion of rt_bvh failed"), std::string::npos) << e.what();
  }
  // The next run resets the unit and works.
  const BvhCase& c = Bvh::hardCase("chain");
  Bvh::expectSameTraces(c.image, c.rays, Bvh::rough(19));
}

// Figures, not a check: the BVH unit and the octree unit on the same bunny
// camera rays, 32 slots, memory latency 20, no jitter or stalls (the defaults
// of TraversalRunOptions). Run with
//   build/tests/rtl/rtl_bvh_tests --gtest_also_run_disabled_tests --gtest_filter='*AgainstTheOctree*'
// LANCER_SWEEP_SIZE sets the image side (default 256).
TEST(RtBvh, DISABLED_AgainstTheOctree) {
  const int side = sweepSide("LANCER_SWEEP_SIZE");
  const test::QuantizedScene q = Bvh::bunny(side, side);
  const BvhImage bvh = Bvh::Traits::image(q.triangles);
  const fx::OctreeImage octree = test::UnitTraits<fx::OctreeUnit>::image(q.triangles);
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
  show("bvh", Bvh::expectSameTraces(bvh, q.rays, TraversalRunOptions{}));
  show("octree", makeTraversalDevice<fx::OctreeUnit>("rtl")->run(octree, q.rays, traces, TraversalRunOptions{}));
}

// The treelet schedule on the RTL (docs/scheduling.md): the hard cases with
// each node its own block, on chips of one and four units, with the stream's
// bubbles and stalls, queue memories that overflow and that do not: every ray
// takes its unbroken walk, and the RTL sets aside the same walks in the same
// cycles as the SystemC model (the same cycles, traces and queue figures).
TEST(RtBvhTreelets, TheRtlSetsTheSameWalksAsideInTheSameCyclesAsTheCycleModel) {
  const auto eachNodeItsBlock = [](fx::BvhImage& image) { image.treeletNodes = 1; };
  EXPECT_GT(expectTreeletRunsLikeTheModel<fx::BvhUnit>(test::bvhHardCases(), eachNodeItsBlock, fx::traverseBvh), 1000u);
}

}  // namespace
}  // namespace lancer::rtltest
