// The Verilated rt_octree against the golden octree model (fx::traverseOctree):
// the shared suite (trav_rtl_suite.h: hard cases, the bunny, one slot and all,
// waveforms, the sweep), and the unit's own cases: its timing, its bad
// configurations, its assertions, what only it has.
#include <gtest/gtest.h>


#include <fmt/format.h>

#include "common/error.h"
#include "driver/devices.h"
#include "driver/traversal_device.h"
#include "support/unit_devices.h"
#include "golden/isect.h"
#include "scene/scene.h"
#include "support/octree_cases.h"
#include "octree/too_deep_image.h"
#include "trav_rtl_suite.h"
#include "trav_rtl_treelets.h"

namespace lancer::rtltest {
namespace {

using fx::OctreeImage;
using test::OctreeCase;

using Octree = RtlUnit<fx::OctreeUnit>;

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
    const TraversalRunStats s = Octree::expectSameTraces(image, rays, o);
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

// Its own bad input (the typed suite has the shared cases).
TEST(RtOctree, RejectsBadConfigurations) {
  const OctreeImage image = fx::buildOctreeImage({}, 1, 8);
  const std::vector<QRay> one{QRay{0, {0, 0, 0}, {kDirMax, 0, 0}}};
  std::vector<fx::TraversalTrace> traces;
  const TraversalRunOptions o;
  EXPECT_THROW(Octree::rtl().run(image, std::vector<QRay>{QRay{0, {1, 2, 3}, {0, 0, 0}}}, traces, o), InputError);
  EXPECT_THROW(Octree::rtl().run(OctreeImage{}, one, traces, o), InputError);
  // An image deeper than the unit's stack (the descriptor's check, as in every model).
  OctreeImage deep = image;
  deep.depth = fx::kOctreeMaxDepth + 1;
  EXPECT_THROW(Octree::rtl().run(deep, one, traces, o), InputError);
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
  expectAssertionFails(Octree::rtl());
  // The next run resets the unit and works.
  const OctreeCase& c = Octree::hardCase("octants");
  Octree::expectSameTraces(c.image, c.rays, Octree::rough(19));
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
  const OctreeCase& c = Octree::hardCase("octants");
  Octree::expectSameTraces(c.image, c.rays, Octree::rough(20), newer);
  expectAssertionFails(older);
  Octree::expectSameTraces(c.image, c.rays, Octree::rough(21), newer);
  Octree::expectSameTraces(c.image, c.rays, Octree::rough(22), older);
  expectAssertionFails(newer);
  Octree::expectSameTraces(c.image, c.rays, Octree::rough(23), older);
}

// The treelet schedule on the RTL (docs/scheduling.md): the hard cases with
// each child group its own block (the maximum-depth cases read groups deeper
// than the suspend window), on chips of one and four units, with the stream's
// bubbles and stalls, queue memories that overflow and that do not: every ray
// takes its unbroken walk, and the RTL sets aside the same walks in the same
// cycles as the SystemC model.
TEST(RtOctreeTreelets, TheRtlSetsTheSameWalksAsideInTheSameCyclesAsTheCycleModel) {
  const auto eachGroupItsBlock = [](OctreeImage& image) { fx::layoutOctreeTreelets(image, fx::kOctreeChildren); };
  EXPECT_GT(expectTreeletRunsLikeTheModel<fx::OctreeUnit>(test::octreeHardCases(), eachGroupItsBlock,
                                                          fx::traverseOctree),
            1000u);
}

}  // namespace
}  // namespace lancer::rtltest
