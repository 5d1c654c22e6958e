// The Verilated rt_grid against the golden grid model (fx::traverseGrid): for
// every ray the same cells in the same order, the same number of tests and the
// same closest hit, bit for bit, under memory latency jitter, output
// backpressure and input bubbles. The hard cases come from tests/support/grid_cases.*,
// shared with the SystemC tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include <fmt/format.h>

#include "common/error.h"
#include "driver/traversal_device.h"
#include "support/unit_devices.h"
#include "support/grid_cases.h"
#include "trav_test_support.h"

namespace lancer::rtltest {
namespace {

using fx::GridImage;

VerilatorGridDevice& rtl() { return sharedDevice<VerilatorGridDevice>(); }

// The RTL beside the golden grid (compareWithGolden), and the cell reads; returns the RTL's stats.
TraversalRunStats expectSameTraces(const GridImage& image, const std::vector<QRay>& rays,
                                   const TraversalRunOptions& options) {
  const std::string where = fmt::format("grid {}x{}x{}", image.res[0], image.res[1], image.res[2]);
  const auto [g, r] = compareWithGolden<GoldenGridDevice>(rtl(), image, rays, options,
                                                          {where, test::describeGridRay, test::describeGridTrace});
  // Cell reads: every cell entered, plus at most CellQueue - 1 prefetched past the last one per ray.
  EXPECT_GE(r.nodeReads, g.nodeReads);
  EXPECT_LE(r.nodeReads, g.nodeReads + (test::kGridCellQueue - 1) * rays.size());
  if (r.steps > 0) {
    // Some slot could step in every cycle with a step, and at most one step per such cycle.
    EXPECT_GE(r.stepReadyCycles, r.steps);
    EXPECT_LE(r.stepReadyCycles, r.cycles);
  }
  return r;
}

TEST(RtGrid, BunnyCameraRays) {
  const test::GridScene q = test::bunnyCamera(40, 40);
  expectSameTraces(test::defaultGridImage(q), q.rays, test::roughGridOptions(1));
}

TEST(RtGrid, HardCases) {
  uint64_t seed = 3;
  for (const test::GridCase& c : test::gridHardCases()) {
    SCOPED_TRACE(c.name);
    expectSameTraces(c.image, c.rays, test::roughGridOptions(++seed));
  }
}

TEST(RtGrid, OneRayInFlightAndAllSlots) {
  const test::GridScene q = test::bunnyCamera(12, 12);
  const GridImage image = test::defaultGridImage(q);
  expectSameTraces(image, q.rays, test::roughGridOptions(15, 1));
  expectSameTraces(image, q.rays, test::roughGridOptions(16, rtl().maxRaysInFlight()));
  TraversalRunOptions fast;  // no jitter, no stalls, latency 1
  fast.memLatency = 1;
  const TraversalRunStats s = expectSameTraces(image, q.rays, fast);
  // Without backpressure a visit is granted in every cycle some slot can step.
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
    const TraversalRunStats s = expectSameTraces(image, rays, o);
    EXPECT_EQ(s.steps, 64u);
    EXPECT_EQ(s.nodeReads, 64u);  // the ray leaves the grid: nothing read past c63
    const int underWay = std::max(32 * (latency + 3), 63 * 3 + latency);
    EXPECT_EQ(s.cycles, uint64_t(2 + fx::kGridSetupLatency + underWay + 4)) << "latency " << latency;
  }
}

TEST(RtGrid, RejectsBadConfigurations) {
  const GridImage image = fx::buildGridImage({}, {1, 1, 1});
  const std::vector<QRay> one{QRay{0, {0, 0, 0}, {kDirMax, 0, 0}}};
  expectRejectsRaysInFlight<GridImage>(rtl(), image, one, "LANCER_GRID_RAYS_IN_FLIGHT");
  std::vector<fx::GridTrace> traces;
  GridImage tooFine = image;
  tooFine.res = {fx::kGridResMax + 1, 1, 1};
  EXPECT_THROW(rtl().run(tooFine, one, traces), InputError);
  // A corrupt image: a cell whose triangles lie outside the index list.
  GridImage broken = image;
  broken.cells[0] = fx::GridCell{5, 1};
  try {
    rtl().run(broken, one, traces);
    FAIL() << "no runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("index list read at 5"), std::string::npos) << e.what();
  }
  // The device still works afterwards.
  expectSameTraces(image, one, TraversalRunOptions{});
}

TEST(RtGrid, WritesAnFstWaveformWhenAsked) {
  std::mt19937_64 rng(17);
  const GridImage image = fx::buildGridImage(test::randomGridTriangles(rng, 20, kPosMax / 4), {4, 4, 4});
  std::vector<QRay> rays;
  for (uint32_t i = 0; i < 8; ++i) rays.push_back(test::randomGridRay(rng, i));
  TraversalRunOptions o = test::roughGridOptions(18);
  o.stream.wavePath = wavePath("rt_grid_wave");
  expectSameTraces(image, rays, o);
  expectWaveform(o.stream.wavePath);
}

// Performance sweep, not a check (docs/grid-unit.md has the table). Run with
//   build/tests/rtl/rtl_grid_tests --gtest_also_run_disabled_tests --gtest_filter='*Sweep*'
// LANCER_GRID_SWEEP_SIZE sets the image side (default 256).
TEST(RtGrid, DISABLED_Sweep) {
  const int side = sweepSide("LANCER_GRID_SWEEP_SIZE");
  const test::GridScene q = test::bunnyCamera(side, side);
  const GridImage image = test::defaultGridImage(q);
  fmt::print("bunny {} tris, grid {}x{}x{}, {} camera rays ({}x{})\n", q.triangles.size(), image.res[0],
             image.res[1], image.res[2], q.rays.size(), side, side);
  printSweep<GridImage>(rtl(), image, q.rays);
}

}  // namespace
}  // namespace lancer::rtltest
