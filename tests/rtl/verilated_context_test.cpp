// Every Verilated device (rt_isect, rt_grid, rt_octree) runs its model in a
// VerilatedContext of its own and makes it the thread's current one before it
// runs: Verilator reports a failed assertion to the *current* context, the
// last one made or selected, so a device that did not select its own would
// lose its failures to (or be stopped by) a model made after it. Several
// devices of every kind are alive here in one program.
#include <gtest/gtest.h>

#include <vector>

#include "Vrt_isect.h"
#include "driver/golden_device.h"
#include "driver/verilated_port.h"
#include "driver/verilated_unit.h"
#include "support/unit_devices.h"
#include "driver/verilator_isect_device.h"
#include "golden/grid.h"
#include "golden/octree.h"
#include "isect/isect_cases.h"
#include "octree/too_deep_image.h"
#include "stream_rule.h"
#include "verilated.h"

namespace lancer {
namespace {

using fx::kDirMax;

void idleIsect(Vrt_isect& top) {
  top.req_valid_i = 0;
  top.res_ready_i = 0;
}

// Breaks the producer's rule on `unit`: fills the pipeline with the consumer
// stalled, offers one more request (refused), then withdraws it; rt_isect's
// a_req_hold fires on the edge after. Returns what the unit threw ("" if nothing).
std::string breakProducerRule(VerilatedUnit<Vrt_isect>& unit) {
  const auto pairs = rtltest::randomPairs(fx::kIsectLatency + 1, 5);
  unit.reset(idleIsect);
  Vrt_isect& top = unit.top();
  fx::RayWire ray;
  fx::TriWire tri;
  const auto offer = [&]() -> std::string {
    for (int cycle = 0; cycle <= fx::kIsectLatency + 2; ++cycle) {
      const auto& pair = pairs[size_t(std::min(cycle, fx::kIsectLatency))];
      fx::packWire(pair.ray, ray);
      fx::packWire(pair.tri, tri);
      writePort(top.req_ray_i, ray.data(), ray.size());
      writePort(top.req_tri_i, tri.data(), tri.size());
      top.req_valid_i = 1;
      unit.step();
    }
    return top.req_ready_o ? "the pipeline was not full" : "";
  };
  return rtltest::withdrawRefused(unit, offer, [](Vrt_isect& t) { t.req_valid_i = 0; });
}

// VerilatedUnit itself: of two units alive, the older one's failure is its own
// (it selects its context in reset()), and the newer one is not disturbed.
TEST(VerilatedContexts, EachUnitReportsItsOwnAssertions) {
  VerilatedUnit<Vrt_isect> older("older_isect");
  VerilatedUnit<Vrt_isect> newer("newer_isect");
  EXPECT_NE(breakProducerRule(older).find("assertion of older_isect failed"), std::string::npos);
  newer.reset(idleIsect);
  EXPECT_NO_THROW(newer.checkAssertions());
  EXPECT_NE(breakProducerRule(newer).find("assertion of newer_isect failed"), std::string::npos);
  older.reset(idleIsect);
  EXPECT_NO_THROW(older.checkAssertions());
}

// A run of the isect device (which does not reset its model) selects its
// context: after it, the thread's current context is the device's, whose
// clock is the device's; a unit made after the device and failing an
// assertion reports it itself, and the device's next run is not touched.
TEST(VerilatedContexts, IsectDeviceSelectsItsOwnContextInEveryRun) {
  const auto pairs = rtltest::randomPairs(200, 7);
  std::vector<fx::IsectResult> want;
  GoldenIsectDevice().run(pairs, want);
  VerilatorIsectDevice device;
  VerilatedUnit<Vrt_isect> newer("newer_isect");  // now the current context
  for (int run = 0; run < 2; ++run) {
    std::vector<fx::IsectResult> got;
    device.run(pairs, got);
    EXPECT_EQ(got, want) << "run " << run;
    EXPECT_EQ(Verilated::threadContextp()->time(), 2 * device.totalCycles()) << "run " << run;
    EXPECT_NE(breakProducerRule(newer).find("assertion of newer_isect failed"), std::string::npos);
  }
}

// The traversal devices likewise, each kind beside the others: the oldest
// device's assertion failure (an octree one level too deep) is its own, while
// grid, isect and octree devices made after it are alive.
TEST(VerilatedContexts, TraversalDevicesReportTheirOwnAssertions) {
  VerilatorOctreeDevice octree;
  VerilatorGridDevice grid;
  VerilatorIsectDevice isect;
  VerilatorOctreeDevice newerOctree;

  // A grid run, then the old octree device fails: its error, not the grid's.
  const fx::GridImage gridImage = fx::buildGridImage({}, {8, 1, 1});
  const std::vector<fx::QRay> alongX{fx::QRay{0, {0, 1, 1}, {kDirMax, 0, 0}}};
  std::vector<fx::TraversalTrace> traces;
  const TraversalRunStats gridRun = grid.run(gridImage, alongX, traces);
  EXPECT_EQ(traces.at(0).visits.size(), 8u);
  // The grid's context is the current one after its run: its clock covers the run.
  EXPECT_GT(Verilated::threadContextp()->time(), 2 * gridRun.cycles);
  try {
    octree.run(rtltest::tooDeepOctreeImage(), rtltest::kTooDeepDiagonalRay, traces);
    ADD_FAILURE() << "no assertion fired";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("assertion of rt_octree failed"), std::string::npos) << e.what();
  }
  // The others still run clean.
  EXPECT_NO_THROW(grid.run(gridImage, alongX, traces));
  EXPECT_EQ(traces.at(0).visits.size(), 8u);
  const fx::OctreeImage octreeImage = fx::buildOctreeImage({}, 1, 8);
  // The same ray on a sound image.
  EXPECT_NO_THROW(newerOctree.run(octreeImage, rtltest::kTooDeepDiagonalRay, traces));
  std::vector<fx::IsectResult> results;
  EXPECT_NO_THROW(isect.run(rtltest::randomPairs(10, 3), results));
  EXPECT_NO_THROW(octree.run(octreeImage, rtltest::kTooDeepDiagonalRay, traces));
}

}  // namespace
}  // namespace lancer
