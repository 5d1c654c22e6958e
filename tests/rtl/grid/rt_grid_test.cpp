// The Verilated rt_grid against the golden grid model (fx::traverseGrid):
// the shared suite (trav_rtl_suite.h: hard cases, the bunny, one slot and all,
// waveforms, the sweep), and the unit's own cases: its timing, its bad
// configurations, what only it has.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include <fmt/format.h>

#include "common/error.h"
#include "driver/traversal_device.h"
#include "support/unit_devices.h"
#include "support/grid_cases.h"
#include "trav_rtl_suite.h"

namespace lancer::rtltest {
namespace {

using fx::GridImage;

using Grid = RtlUnit<fx::GridUnit>;

// The grid's own invariant: without backpressure a visit is granted in every
// cycle some slot can step.
TEST(RtGrid, StepsInEveryCycleAStepIsReadyWithoutBackpressure) {
  const auto c = Grid::bunnyCase(12);
  TraversalRunOptions fast;  // no jitter, no stalls, latency 1
  fast.memLatency = 1;
  const TraversalRunStats s = Grid::expectSameTraces(c.image, c.rays, fast);
  EXPECT_EQ(s.stepReadyCycles, s.steps);
}

// docs/grid-unit.md, "Timing of one ray": through empty cells a slot enters
// CellQueue cells per L + 3 cycles once under way, and reads at most one cell
// every three cycles (the grant; the frontier's step; its next step's
// preparation). One ray along +x through 64 empty cells, offered in cycle 0:
// cell c0 is entered in cycle e = 2 + GRID_SETUP_LATENCY; with a slow memory
// the cells c(2j-1) and c(2j) follow in cycles e + j(L+3) + 1 and
// e + j(L+3) + 2 (the read of c1 waits two cycles behind c0's); with a fast
// one (L < 3) the reads, one every three cycles, are the pace and c63's read
// goes out 63 * 3 cycles after c0's. The last cell ends the ray, whose result
// is taken two cycles later.
TEST(RtGrid, TimingOfOneRayThroughEmptyCells) {
  if (test::kGridCellQueue != 2) GTEST_SKIP() << "the cycle counts below are CellQueue = 2's";
  const GridImage image = fx::buildGridImage({}, {64, 1, 1});
  const std::vector<QRay> rays{QRay{0, {0, kPosMax / 2, kPosMax / 2}, {kDirMax, 0, 0}}};
  for (int latency : {1, 2, 3, 4, 7, 20}) {
    TraversalRunOptions o;
    o.memLatency = latency;
    const TraversalRunStats s = Grid::expectSameTraces(image, rays, o);
    EXPECT_EQ(s.steps, 64u);
    EXPECT_EQ(s.nodeReads, 64u);  // the ray leaves the grid: nothing read past c63
    const int underWay = std::max(32 * (latency + 3), 63 * 3 + latency);
    EXPECT_EQ(s.cycles, uint64_t(2 + fx::kGridSetupLatency + underWay + 4)) << "latency " << latency;
  }
}

// Its own bad input (the typed suite has the shared cases).
TEST(RtGrid, RejectsBadConfigurations) {
  const GridImage image = fx::buildGridImage({}, {1, 1, 1});
  const std::vector<QRay> one{QRay{0, {0, 0, 0}, {kDirMax, 0, 0}}};
  std::vector<fx::GridTrace> traces;
  GridImage tooFine = image;
  tooFine.res = {fx::kGridResMax + 1, 1, 1};
  EXPECT_THROW(Grid::rtl().run(tooFine, one, traces), InputError);
}

}  // namespace
}  // namespace lancer::rtltest
