// The Verilated rt_grid against the golden grid model (fx::traverseGrid): for
// every ray the same cells in the same order, the same number of tests and the
// same closest hit, bit for bit, under memory latency jitter, output
// backpressure and input bubbles. The hard cases come from tests/support/grid_cases.*,
// shared with the SystemC tests.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>

#include <fmt/format.h>

#include "common/error.h"
#include "driver/traversal_device.h"
#include "driver/verilator_grid_device.h"
#include "support/grid_cases.h"

namespace lancer {
namespace {

using fx::GridImage;
using fx::kDirMax;
using fx::kPosMax;
using fx::QRay;
using test::bunnyCamera;
using test::defaultGridImage;
using test::GridScene;
using test::roughGridOptions;

VerilatorGridDevice& rtl() {
  static VerilatorGridDevice device;
  return device;
}

// Runs both devices, expects equal traces per ray; returns the RTL's stats.
TraversalRunStats expectSameTraces(const GridImage& image, const std::vector<QRay>& rays,
                                   const TraversalRunOptions& options) {
  GoldenGridDevice golden;
  std::vector<fx::GridTrace> want, got;
  const TraversalRunStats g = golden.run(image, rays, want, options);
  const TraversalRunStats r = rtl().run(image, rays, got, options);
  EXPECT_EQ(got.size(), want.size());
  int reported = 0;
  for (size_t k = 0; k < std::min(got.size(), want.size()); ++k) {
    if (got[k] == want[k]) continue;
    ADD_FAILURE() << "grid " << image.res[0] << "x" << image.res[1] << "x" << image.res[2] << ", "
                  << test::describeGridRay(rays[k]) << "\n  rtl:    " << test::describeGridTrace(got[k])
                  << "\n  golden: " << test::describeGridTrace(want[k]);
    if (++reported == 5) break;
  }
  EXPECT_EQ(r.steps, g.steps);
  // Cell reads: every cell entered, plus at most CellQueue - 1 prefetched past the last one per ray.
  EXPECT_GE(r.nodeReads, g.nodeReads);
  EXPECT_LE(r.nodeReads, g.nodeReads + (test::kGridCellQueue - 1) * rays.size());
  EXPECT_EQ(r.indexReads, g.indexReads);
  EXPECT_EQ(r.triangleReads, g.triangleReads);
  EXPECT_EQ(r.isectTests, g.isectTests);
  EXPECT_EQ(r.rays, rays.size());
  EXPECT_TRUE(r.cycleAccurate);
  if (r.steps > 0) {
    // Some slot could step in every cycle with a step, and at most one step per such cycle.
    EXPECT_GE(r.stepReadyCycles, r.steps);
    EXPECT_LE(r.stepReadyCycles, r.cycles);
  }
  return r;
}

TEST(RtGrid, BunnyCameraRays) {
  const GridScene q = bunnyCamera(40, 40);
  expectSameTraces(defaultGridImage(q), q.rays, roughGridOptions(1));
}

TEST(RtGrid, HardCases) {
  uint64_t seed = 3;
  for (const test::GridCase& c : test::gridHardCases()) {
    SCOPED_TRACE(c.name);
    expectSameTraces(c.image, c.rays, roughGridOptions(++seed));
  }
}

TEST(RtGrid, OneRayInFlightAndAllSlots) {
  const GridScene q = bunnyCamera(12, 12);
  const GridImage image = defaultGridImage(q);
  expectSameTraces(image, q.rays, roughGridOptions(15, 1));
  expectSameTraces(image, q.rays, roughGridOptions(16, rtl().maxRaysInFlight()));
  TraversalRunOptions fast;  // no jitter, no stalls, latency 1
  fast.memLatency = 1;
  const TraversalRunStats s = expectSameTraces(image, q.rays, fast);
  // Without backpressure a visit is granted in every cycle some slot can step.
  EXPECT_EQ(s.stepReadyCycles, s.steps);
}

// docs/grid-unit.md, "Timing of one ray": through empty cells a slot enters
// CellQueue cells per L + 3 cycles once under way. One ray along +x through
// 64 empty cells, offered in cycle 0: cell c0 is entered in cycle 4, cells
// c(2j-1) and c(2j) in cycles 3 + j(L+3) and 4 + j(L+3); the last, c63, ends
// the ray in cycle 3 + 32(L+3), whose result is taken two cycles later.
TEST(RtGrid, TimingOfOneRayThroughEmptyCells) {
  if (test::kGridCellQueue != 2) GTEST_SKIP() << "the cycle counts below are CellQueue = 2's";
  const GridImage image = fx::buildGridImage({}, {64, 1, 1});
  const std::vector<QRay> rays{QRay{0, {0, kPosMax / 2, kPosMax / 2}, {kDirMax, 0, 0}}};
  for (int latency : {1, 7, 20}) {
    TraversalRunOptions o;
    o.memLatency = latency;
    const TraversalRunStats s = expectSameTraces(image, rays, o);
    EXPECT_EQ(s.steps, 64u);
    EXPECT_EQ(s.nodeReads, 64u);  // the ray leaves the grid: nothing read past c63
    EXPECT_EQ(s.cycles, uint64_t(6 + 32 * (latency + 3))) << "latency " << latency;
  }
}

TEST(RtGrid, RejectsTooManyRaysInFlight) {
  const GridImage image = fx::buildGridImage({}, {1, 1, 1});
  std::vector<fx::GridTrace> traces;
  TraversalRunOptions o;
  o.raysInFlight = rtl().maxRaysInFlight() + 1;
  try {
    rtl().run(image, std::vector<QRay>{QRay{0, {0, 0, 0}, {kDirMax, 0, 0}}}, traces, o);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(std::to_string(o.raysInFlight)), std::string::npos) << what;
    EXPECT_NE(what.find(std::to_string(rtl().maxRaysInFlight())), std::string::npos) << what;
  }
  o.raysInFlight = -1;
  EXPECT_THROW(rtl().run(image, std::vector<QRay>{}, traces, o), InputError);
}

TEST(RtGrid, WritesAnFstWaveformWhenAsked) {
  std::mt19937_64 rng(17);
  const GridImage image = fx::buildGridImage(test::randomGridTriangles(rng, 20, kPosMax / 4), {4, 4, 4});
  std::vector<QRay> rays;
  for (uint32_t i = 0; i < 8; ++i) rays.push_back(test::randomGridRay(rng, i));
  TraversalRunOptions o = roughGridOptions(18);
  o.stream.wavePath = ::testing::TempDir() + "rt_grid_wave.fst";
  std::remove(o.stream.wavePath.c_str());
  expectSameTraces(image, rays, o);
  std::FILE* f = std::fopen(o.stream.wavePath.c_str(), "rb");
  ASSERT_NE(f, nullptr) << o.stream.wavePath;
  std::fseek(f, 0, SEEK_END);
  EXPECT_GT(std::ftell(f), 1000);
  std::fclose(f);
  std::remove(o.stream.wavePath.c_str());
}

// Performance sweep, not a check (docs/grid-unit.md has the table). Run with
//   build/tests/rtl/rtl_grid_tests --gtest_also_run_disabled_tests --gtest_filter='*Sweep*'
// LANCER_GRID_SWEEP_SIZE sets the image side (default 256).
TEST(RtGrid, DISABLED_Sweep) {
  const char* sizeEnv = std::getenv("LANCER_GRID_SWEEP_SIZE");
  const int side = sizeEnv ? std::atoi(sizeEnv) : 256;
  const GridScene q = bunnyCamera(side, side);
  const GridImage image = defaultGridImage(q);
  fmt::print("bunny {} tris, grid {}x{}x{}, {} camera rays ({}x{})\n", q.triangles.size(), image.res[0],
             image.res[1], image.res[2], q.rays.size(), side, side);
  fmt::print("{:>6} {:>7} {:>10} {:>9} {:>9} {:>11} {:>10} {:>13} {:>11}\n", "slots", "latency", "cycles",
             "tests/cyc", "steps/cyc", "steps/rdy", "isect busy", "Mrays/s@500M", "host ray/s");
  auto one = [&](int slots, int latency) {
    TraversalRunOptions o;
    o.memLatency = latency;
    o.raysInFlight = slots;
    std::vector<fx::GridTrace> traces;
    const auto start = std::chrono::steady_clock::now();
    const TraversalRunStats st = rtl().run(image, q.rays, traces, o);
    const double host = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double c = double(st.cycles);
    fmt::print("{:>6} {:>7} {:>10} {:>9.3f} {:>9.3f} {:>11.3f} {:>9.1f}% {:>13.2f} {:>11.0f}\n", slots, latency,
               st.cycles, double(st.isectTests) / c, double(st.steps) / c,
               double(st.steps) / double(std::max<uint64_t>(st.stepReadyCycles, 1)),
               100.0 * double(st.isectBusyCycles) / c, double(st.rays) / c * 500.0, double(st.rays) / host);
  };
  const int max = rtl().maxRaysInFlight();
  for (int slots : {1, 4, 8, 16, 32}) {
    if (slots <= max) one(slots, 20);
  }
  for (int latency : {1, 10, 50, 100}) one(max, latency);
}

}  // namespace
}  // namespace lancer
