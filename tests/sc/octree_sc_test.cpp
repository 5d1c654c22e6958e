// The SystemC side of rt_octree beyond the shared suite (trav_sc_suite.h, run
// over the unit by trav_sc_units.cpp): the timing the micro-architecture
// prescribes (docs/octree-unit.md), on the cycle model and the Verilated RTL.
#include <gtest/gtest.h>

#include <vector>

#include "golden/octree.h"
#include "support/octree_cases.h"
#include "trav_sc_suite.h"
#include "trav_sc_treelets.h"

namespace lancer {
namespace {

using fx::kDirMax;
using fx::kPosBits;
using fx::QRay;
using fx::QTriangle;

class ScOctree : public test::ScTraversalTest<SystemCOctreeDevice> {};

INSTANTIATE_TEST_SUITE_P(Impl, ScOctree, ::testing::Values(SystemCImpl::Model, SystemCImpl::Pins, SystemCImpl::Rtl),
                         test::implName<SystemCImpl>);

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
      ASSERT_EQ(t.visits.size(), 3u) << test::UnitTraits<fx::OctreeUnit>::describeTrace(t);
      ASSERT_TRUE(image.nodes[t.visits[1]].leaf && image.nodes[t.visits[1]].count == 0) << test::UnitTraits<fx::OctreeUnit>::describeTrace(t);
      ASSERT_TRUE(image.nodes[t.visits[2]].leaf && image.nodes[t.visits[2]].count == 0) << test::UnitTraits<fx::OctreeUnit>::describeTrace(t);
      EXPECT_EQ(cycles, e + 12 + uint64_t(latency)) << "latency " << latency;
    }
  }
}

// The treelet schedule on the cycle model (docs/scheduling.md): every hard
// case laid out with each child group its own treelet block (the most
// suspensions; the maximum-depth cases read groups deeper than the suspend
// window), on one unit with a queue memory that holds the walks and on four
// with one too small for them (overflow to DRAM), with the stream's bubbles
// and stalls: every ray takes its unbroken walk, bit for bit, and the
// units set aside exactly the golden walk's suspensions. A run is the same
// twice and whatever the host threads.
TEST(ScOctreeTreelets, SuspendedWalksTakeTheUnbrokenWalkThroughTheRayQueues) {
  SystemCOctreeDevice device(SystemCImpl::Model);
  mem::RayQueueStats all;
  fx::TreeletCrossings every;
  for (test::OctreeCase c : test::octreeHardCases()) {
    fx::layoutOctreeTreelets(c.image, fx::kOctreeChildren);
    fx::TreeletCrossings expected;
    for (const QRay& ray : c.rays) expected += fx::octreeTreeletCrossings(c.image, ray);
    every += expected;
    test::checkTreeletRuns(device, c.name, c.image, c.rays, expected.suspensions, fx::traverseOctree, all);
  }
  EXPECT_GT(every.crossings, every.suspensions) << "the window's limit is met";
  EXPECT_GT(all.suspensions, 1000u);
  EXPECT_GT(all.overflows, 0u);
  EXPECT_GT(all.bytesWritten, 0u);
}

}  // namespace
}  // namespace lancer
