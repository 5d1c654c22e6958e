// The SystemC side of rt_grid: the cycle model ("systemc"), the Verilated RTL in
// SystemC ("rtl-systemc") and the mixed system (cycle model with the Verilated
// rt_isect) against the golden grid model, against each other cycle for cycle,
// and against the C++ Verilated device ("rtl").
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "common/error.h"
#include "driver/devices.h"
#include "driver/golden_device.h"
#include "driver/systemc_grid_device.h"
#include "driver/systemc_isect_device.h"
#include "driver/verilator_grid_device.h"
#include "support/grid_cases.h"

namespace lancer {
namespace sc {
void PrintTo(const GridCycle& c, std::ostream* os) {
  *os << fmt::format(
      "cycle {}: ray {}{} res {}{} visit {}{} cell {}@{:#x}/{} idx {}@{:#x}/{} tri {}@{:#x}/{} fire {} step ready {} "
      "res [{:x}] visit [{:x}]",
      c.cycle, int(c.rayValid), int(c.rayReady), int(c.resValid), int(c.resReady), int(c.visitValid),
      int(c.visitReady), int(c.cellReq), c.cellAddr, c.cellTag, int(c.idxReq), c.idxAddr, c.idxTag, int(c.triReq),
      c.triAddr, c.triTag, int(c.perfIsectFire), int(c.perfStepReady), fmt::join(c.resData, "_"),
      fmt::join(c.visitData, "_"));
}
}  // namespace sc

namespace {

using Impl = SystemCGridDevice::Impl;
using test::roughGridOptions;

bool available(Impl impl) {
  if (impl == Impl::Rtl) return SystemCGridDevice::rtlAvailable();
  if (impl == Impl::ModelRtlIsect) return SystemCGridDevice::rtlIsectAvailable();
  return true;
}

// Runs golden and `device`, expects identical traces and golden's counters.
TraversalRunStats expectSameTraces(GridDevice& device, const fx::GridImage& image, const std::vector<fx::QRay>& rays,
                              const TraversalRunOptions& options, const std::string& what) {
  GoldenGridDevice golden;
  std::vector<fx::GridTrace> want, got;
  const TraversalRunStats g = golden.run(image, rays, want, options);
  const TraversalRunStats r = device.run(image, rays, got, options);
  EXPECT_EQ(got.size(), want.size()) << what;
  int reported = 0;
  for (size_t k = 0; k < std::min(got.size(), want.size()); ++k) {
    if (got[k] == want[k]) continue;
    ADD_FAILURE() << what << ": grid " << image.res[0] << "x" << image.res[1] << "x" << image.res[2] << ", "
                  << test::describeGridRay(rays[k]) << "\n  " << device.name() << ": " << test::describeGridTrace(got[k])
                  << "\n  golden: " << test::describeGridTrace(want[k]);
    if (++reported == 5) break;
  }
  EXPECT_EQ(r.rays, rays.size()) << what;
  EXPECT_EQ(r.steps, g.steps) << what;
  // Cell reads: every cell entered, plus at most CellQueue - 1 prefetched past the last one per ray.
  EXPECT_GE(r.nodeReads, g.nodeReads) << what;
  EXPECT_LE(r.nodeReads, g.nodeReads + (test::kGridCellQueue - 1) * rays.size()) << what;
  EXPECT_EQ(r.indexReads, g.indexReads) << what;
  EXPECT_EQ(r.triangleReads, g.triangleReads) << what;
  EXPECT_EQ(r.isectTests, g.isectTests) << what;
  EXPECT_EQ(r.isectBusyCycles, r.isectTests) << what;
  EXPECT_TRUE(r.cycleAccurate) << what;
  EXPECT_GT(r.cycles, 0u) << what;
  return r;
}

void expectSameStats(const TraversalRunStats& a, const TraversalRunStats& b, const std::string& what) {
  EXPECT_EQ(a.cycles, b.cycles) << what;
  EXPECT_EQ(a.rays, b.rays) << what;
  EXPECT_EQ(a.steps, b.steps) << what;
  EXPECT_EQ(a.nodeReads, b.nodeReads) << what;
  EXPECT_EQ(a.indexReads, b.indexReads) << what;
  EXPECT_EQ(a.triangleReads, b.triangleReads) << what;
  EXPECT_EQ(a.isectTests, b.isectTests) << what;
  EXPECT_EQ(a.isectBusyCycles, b.isectBusyCycles) << what;
  EXPECT_EQ(a.stepReadyCycles, b.stepReadyCycles) << what;
}

// ---- Each implementation against the golden model ---------------------------

class ScGrid : public ::testing::TestWithParam<Impl> {
 protected:
  void SetUp() override {
    if (!available(GetParam())) GTEST_SKIP() << "this build has no Verilated RTL for this variant";
  }
};

std::string implName(const ::testing::TestParamInfo<Impl>& info) {
  switch (info.param) {
    case Impl::Model: return "Model";
    case Impl::Rtl: return "Rtl";
    case Impl::ModelRtlIsect: return "ModelRtlIsect";
  }
  return "?";
}

INSTANTIATE_TEST_SUITE_P(Impl, ScGrid, ::testing::Values(Impl::Model, Impl::Rtl, Impl::ModelRtlIsect), implName);

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
  std::vector<fx::GridTrace> a, b, c;
  SystemCGridDevice first(GetParam());
  const TraversalRunStats sa = first.run(image, q.rays, a, roughGridOptions(3));
  const TraversalRunStats other = first.run(image, q.rays, b, roughGridOptions(4));
  SystemCGridDevice second(GetParam());
  const TraversalRunStats sc = second.run(image, q.rays, c, roughGridOptions(3));
  EXPECT_EQ(a, c);
  EXPECT_EQ(a, b);  // traces do not depend on the timing
  expectSameStats(sa, sc, "same seed, new device");
  EXPECT_NE(sa.cycles, other.cycles);
}

TEST_P(ScGrid, EmptyRunAndInvalidOptions) {
  SystemCGridDevice device(GetParam());
  const fx::GridImage image = fx::buildGridImage({}, {1, 1, 1});
  std::vector<fx::GridTrace> traces(3);
  const TraversalRunStats s = device.run(image, std::vector<fx::QRay>{}, traces);
  EXPECT_TRUE(traces.empty());
  EXPECT_EQ(s.cycles, 0u);
  const std::vector<fx::QRay> one{fx::QRay{0, {0, 0, 0}, {fx::kDirMax, 0, 0}}};
  TraversalRunOptions o;
  o.raysInFlight = device.maxRaysInFlight() + 1;
  try {
    device.run(image, one, traces, o);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(std::to_string(o.raysInFlight)), std::string::npos) << what;
    EXPECT_NE(what.find(std::to_string(device.maxRaysInFlight())), std::string::npos) << what;
  }
  o = {};
  o.raysInFlight = -1;
  EXPECT_THROW(device.run(image, one, traces, o), InputError);
  o = {};
  o.memLatency = 0;
  EXPECT_THROW(device.run(image, one, traces, o), InputError);
  o = {};
  o.stream.outputStallProbability = 1.0;
  EXPECT_THROW(device.run(image, one, traces, o), InputError);
  // Still usable afterwards.
  expectSameTraces(device, image, one, {}, "after errors");
}

// ---- Cycle accuracy -------------------------------------------------------------

std::vector<TraversalRunOptions> timingSettings() {
  std::vector<TraversalRunOptions> all;
  TraversalRunOptions o;
  all.push_back(o);  // latency 20, nothing random
  o.memLatency = 1;
  all.push_back(o);
  all.push_back(roughGridOptions(31));
  o = roughGridOptions(32, 3);
  all.push_back(o);
  o = roughGridOptions(33);
  o.memLatency = 40;
  o.memLatencyJitter = 40;
  o.stream.outputStallProbability = 0.6;
  all.push_back(o);
  return all;
}

std::string optionsText(const TraversalRunOptions& o) {
  return fmt::format("latency {} jitter {} slots {} stall {} idle {} seed {}", o.memLatency, o.memLatencyJitter,
                     o.raysInFlight, o.stream.outputStallProbability, o.stream.inputIdleProbability, o.stream.seed);
}

TEST(ScGridCycleAccuracy, ModelMatchesVerilatedRtlCycleForCycle) {
  if (!SystemCGridDevice::rtlAvailable()) GTEST_SKIP() << "no Verilated rt_grid in this build";
  const test::GridScene q = test::bunnyCamera(16, 16);
  const fx::GridImage image = fx::buildGridImage(q.triangles, fx::chooseGridResolution(q.triangles));
  std::vector<test::GridCase> cases{{"bunny 16x16", image, q.rays}};
  for (test::GridCase& c : test::gridHardCases()) {
    if (c.name.rfind("crowded", 0) == 0 || c.name.rfind("planes", 0) == 0) cases.push_back(std::move(c));
  }
  SystemCGridDevice model(Impl::Model), rtl(Impl::Rtl);
  for (const test::GridCase& c : cases) {
    for (const TraversalRunOptions& o : timingSettings()) {
      const std::string what = c.name + ", " + optionsText(o);
      std::vector<sc::GridCycle> mt, rt;
      std::vector<fx::GridTrace> a, b;
      model.setCycleTrace(&mt);
      rtl.setCycleTrace(&rt);
      const TraversalRunStats sm = model.run(c.image, c.rays, a, o);
      const TraversalRunStats sr = rtl.run(c.image, c.rays, b, o);
      model.setCycleTrace(nullptr);
      rtl.setCycleTrace(nullptr);
      expectSameStats(sm, sr, what);
      EXPECT_EQ(a, b) << what;
      ASSERT_EQ(mt.size(), rt.size()) << what;
      size_t differing = 0;
      for (size_t i = 0; i < mt.size(); ++i) {
        if (mt[i] == rt[i]) continue;
        if (++differing <= 3) {
          ADD_FAILURE() << what << "\n  model: " << ::testing::PrintToString(mt[i])
                        << "\n  rtl:   " << ::testing::PrintToString(rt[i]);
        }
      }
      EXPECT_EQ(differing, 0u) << what << ": cycles whose port activity differs";
    }
  }
}

TEST(ScGridCycleAccuracy, StatsEqualTheCxxVerilatedDevice) {
  const test::GridScene q = test::bunnyCamera(16, 16);
  const fx::GridImage image = fx::buildGridImage(q.triangles, fx::chooseGridResolution(q.triangles));
  VerilatorGridDevice cxx;
  std::vector<Impl> impls{Impl::Model};
  if (SystemCGridDevice::rtlAvailable()) impls.push_back(Impl::Rtl);
  if (SystemCGridDevice::rtlIsectAvailable()) impls.push_back(Impl::ModelRtlIsect);
  for (const TraversalRunOptions& o : timingSettings()) {
    std::vector<fx::GridTrace> want, got;
    const TraversalRunStats ref = cxx.run(image, q.rays, want, o);
    for (Impl impl : impls) {
      SystemCGridDevice device(impl);
      const TraversalRunStats s = device.run(image, q.rays, got, o);
      const std::string what = fmt::format("{} vs rtl, {}", device.name(), optionsText(o));
      expectSameStats(s, ref, what);
      EXPECT_EQ(got, want) << what;
    }
  }
}

// ---- The device in the process --------------------------------------------------

TEST(ScGridDevice, NamesAndFactory) {
  const std::vector<std::string> names = gridDeviceNames();
  EXPECT_NE(std::find(names.begin(), names.end(), "systemc"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "rtl"), names.end());
  EXPECT_EQ(std::find(names.begin(), names.end(), "rtl-systemc") != names.end(), SystemCGridDevice::rtlAvailable());
  for (const std::string& n : names) EXPECT_EQ(makeGridDevice(n)->name(), n);
  EXPECT_EQ(makeGridDevice("systemc")->maxRaysInFlight(), VerilatorGridDevice().maxRaysInFlight());
  EXPECT_THROW(makeGridDevice("nope"), InputError);
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
  if (!SystemCGridDevice::rtlAvailable() || !SystemCGridDevice::wavesAvailable()) {
    GTEST_SKIP() << "no Verilated rt_grid with FST tracing in this build";
  }
  const test::GridScene q = test::bunnyCamera(3, 3);
  const fx::GridImage image = fx::buildGridImage(q.triangles, {8, 8, 8});
  TraversalRunOptions o = roughGridOptions(50);
  o.stream.wavePath = ::testing::TempDir() + "rt_grid_sc_wave.fst";
  std::remove(o.stream.wavePath.c_str());
  SystemCGridDevice rtl(Impl::Rtl);
  expectSameTraces(rtl, image, q.rays, o, "with waves");
  std::FILE* f = std::fopen(o.stream.wavePath.c_str(), "rb");
  ASSERT_NE(f, nullptr) << o.stream.wavePath;
  std::fseek(f, 0, SEEK_END);
  EXPECT_GT(std::ftell(f), 1000);
  std::fclose(f);
  std::remove(o.stream.wavePath.c_str());
}

}  // namespace
}  // namespace lancer
