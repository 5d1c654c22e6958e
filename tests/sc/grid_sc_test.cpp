// The SystemC side of rt_grid: the cycle model ("systemc"), the Verilated RTL in
// SystemC ("rtl-systemc") and the mixed system (cycle model with the Verilated
// rt_isect) against the golden grid model, against each other cycle for cycle,
// and against the C++ Verilated device ("rtl").
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "driver/devices.h"
#include "driver/golden_device.h"
#include "support/unit_devices.h"
#include "driver/systemc_isect_device.h"
#include "support/grid_cases.h"
#include "trav_sc_fixture.h"

namespace lancer {
namespace {

using Impl = SystemCGridDevice::Impl;
using test::expectSameStats;
using test::optionsText;
using test::roughGridOptions;

const test::Describe<fx::GridImage> kDescribe{
    [](const fx::GridImage& image) {
      return fmt::format("grid {}x{}x{}", image.res[0], image.res[1], image.res[2]);
    },
    test::describeGridRay, test::describeGridTrace};

// Runs golden and `device`, expects identical traces and golden's counters;
// cell reads: every cell entered, plus at most CellQueue - 1 prefetched past the last one per ray.
TraversalRunStats expectSameTraces(GridDevice& device, const fx::GridImage& image, const std::vector<fx::QRay>& rays,
                                   const TraversalRunOptions& options, const std::string& what) {
  GoldenGridDevice golden;
  const auto [g, r] = test::expectGoldenTraces<fx::GridImage>(golden, device, image, rays, options, what, kDescribe);
  EXPECT_GE(r.nodeReads, g.nodeReads) << what;
  EXPECT_LE(r.nodeReads, g.nodeReads + (test::kGridCellQueue - 1) * rays.size()) << what;
  return r;
}

// ---- Each implementation against the golden model ---------------------------

class ScGrid : public test::ScTraversalTest<SystemCGridDevice> {};

INSTANTIATE_TEST_SUITE_P(Impl, ScGrid, ::testing::Values(Impl::Model, Impl::Rtl, Impl::ModelRtlIsect),
                         test::implName<Impl>);

TEST_P(ScGrid, MatchesGoldenOnBunnyCameraRays) {
  const test::GridScene q = test::bunnyCamera(32, 32);
  const fx::GridImage image = fx::buildGridImage(q.triangles, fx::chooseGridResolution(q.triangles));
  SystemCGridDevice device(GetParam());
  expectSameTraces(device, image, q.rays, roughGridOptions(1), "bunny 32x32, rough");
}

TEST_P(ScGrid, MatchesGoldenOnHardCases) {
  SystemCGridDevice device(GetParam());
  uint64_t seed = 20;
  for (const test::GridCase& c : test::gridHardCases()) {
    SCOPED_TRACE(c.name);
    expectSameTraces(device, c.image, c.rays, roughGridOptions(++seed), c.name);
  }
}

TEST_P(ScGrid, MatchesGoldenWithOneSlotAllSlotsAndNoBackpressure) {
  const test::GridScene q = test::bunnyCamera(10, 10);
  const fx::GridImage image = fx::buildGridImage(q.triangles, fx::chooseGridResolution(q.triangles));
  SystemCGridDevice device(GetParam());
  expectSameTraces(device, image, q.rays, roughGridOptions(15, 1), "one slot");
  expectSameTraces(device, image, q.rays, roughGridOptions(16, device.maxRaysInFlight()), "all slots");
  TraversalRunOptions fast;  // no jitter, no stalls, latency 1
  fast.memLatency = 1;
  expectSameTraces(device, image, q.rays, fast, "latency 1, no backpressure");
}

TEST_P(ScGrid, RepeatedRunsAreIndependentAndReproducible) {
  const test::GridScene q = test::bunnyCamera(6, 6);
  const fx::GridImage image = fx::buildGridImage(q.triangles, fx::chooseGridResolution(q.triangles));
  test::expectRepeatableRuns<SystemCGridDevice>(GetParam(), image, q.rays, roughGridOptions(3), roughGridOptions(4));
}

TEST_P(ScGrid, EmptyRunAndInvalidOptions) {
  SystemCGridDevice device(GetParam());
  const fx::GridImage image = fx::buildGridImage({}, {1, 1, 1});
  test::expectEmptyRun<fx::GridImage>(device, image);
  test::expectInvalidOptionsRejected<fx::GridImage>(device, image);
  // Still usable afterwards.
  const std::vector<fx::QRay> one{fx::QRay{0, {0, 0, 0}, {fx::kDirMax, 0, 0}}};
  expectSameTraces(device, image, one, {}, "after errors");
}

// ---- Cycle accuracy -------------------------------------------------------------

std::vector<TraversalRunOptions> timingSettings() { return test::timingSettings(roughGridOptions, 31, 32, 33); }

test::GridCase bunnyCase() {
  const test::GridScene q = test::bunnyCamera(16, 16);
  return {"bunny 16x16", fx::buildGridImage(q.triangles, fx::chooseGridResolution(q.triangles)), q.rays};
}

TEST(ScGridCycleAccuracy, ModelMatchesVerilatedRtlCycleForCycle) {
  std::vector<test::GridCase> cases{bunnyCase()};
  for (test::GridCase& c : test::gridHardCases()) {
    if (c.name.rfind("crowded", 0) == 0 || c.name.rfind("planes", 0) == 0) cases.push_back(std::move(c));
  }
  test::expectModelMatchesRtlCycleForCycle<SystemCGridDevice>(cases, timingSettings());
}

TEST(ScGridCycleAccuracy, StatsEqualTheCxxVerilatedDevice) {
  test::expectStatsEqualTheCxxVerilatedDevice<fx::GridUnit, SystemCGridDevice>(
      std::vector<test::GridCase>{bunnyCase()}, timingSettings(), {Impl::Model, Impl::Rtl, Impl::ModelRtlIsect});
}

// ---- The device in the process --------------------------------------------------

TEST(ScGridDevice, NamesAndFactory) {
  test::expectNamesAndFactory<fx::GridUnit, SystemCGridDevice>(VerilatorGridDevice().maxRaysInFlight());
}

TEST(ScGridDevice, GridAndIsectDevicesShareOneKernel) {
  // Either unit's SystemC system may run first; both are elaborated together.
  const test::GridScene q = test::bunnyCamera(4, 4);
  const fx::GridImage image = fx::buildGridImage(q.triangles, {8, 8, 8});
  std::vector<IsectRequest> pairs;
  for (size_t i = 0; i < 20; ++i) pairs.push_back({q.rays[i % q.rays.size()], q.triangles[i]});
  std::vector<fx::IsectResult> want, got;
  GoldenIsectDevice().run(pairs, want);
  for (int round = 0; round < 2; ++round) {
    SystemCIsectDevice isect;
    got.clear();
    isect.run(pairs, got);
    EXPECT_EQ(got, want);
    SystemCGridDevice grid;
    expectSameTraces(grid, image, q.rays, roughGridOptions(40 + round), "interleaved");
  }
}

TEST(ScGridDevice, WaveformOfTheRtlOnRequest) {
  const test::GridScene q = test::bunnyCamera(3, 3);
  const fx::GridImage image = fx::buildGridImage(q.triangles, {8, 8, 8});
  test::expectRtlWave<SystemCGridDevice>("rt_grid_sc_wave.fst", roughGridOptions(50),
                          [&](SystemCGridDevice& rtl, const TraversalRunOptions& o) {
                            expectSameTraces(rtl, image, q.rays, o, "with waves");
                          });
}

}  // namespace
}  // namespace lancer
