// The SystemC side of rt_isect: the cycle model on value ports ("systemc", the
// fast path), the same model on pins in the kernel ("systemc-pins") and the
// Verilated RTL in SystemC ("rtl-systemc") against the golden model, against
// each other cycle for cycle, and against the C++ Verilated RTL device ("rtl").
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <span>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "driver/golden_device.h"
#include "driver/systemc_isect_device.h"
#include "driver/verilator_isect_device.h"
#include "isect_stimulus.h"

namespace lancer {
namespace sc {
// How gtest shows a cycle of the trace.
void PrintTo(const IsectCycle& c, std::ostream* os) {
  *os << fmt::format("cycle {}: req valid {} ready {}, res valid {} ready {}, data {}", c.cycle, c.reqValid,
                     c.reqReady, c.resValid, c.resReady, fmt::join(c.resData, "_"));
}
}  // namespace sc

namespace {

using Impl = SystemCIsectDevice::Impl;
using sc::IsectCycle;
using sctest::describe;

constexpr uint64_t kLatency = fx::kIsectLatency;

std::vector<fx::IsectResult> golden(std::span<const IsectRequest> requests) {
  std::vector<fx::IsectResult> results;
  GoldenIsectDevice().run(requests, results);
  return results;
}

// Bit patterns in request order; the first few differences as reproducers.
void expectSameResults(std::span<const IsectRequest> requests, const std::vector<fx::IsectResult>& expected,
                       const std::vector<fx::IsectResult>& actual, std::string_view who) {
  ASSERT_EQ(actual.size(), expected.size()) << who;
  size_t mismatches = 0;
  for (size_t i = 0; i < actual.size(); ++i) {
    if (actual[i] == expected[i]) continue;
    if (++mismatches <= 5) {
      ADD_FAILURE() << who << " differs from golden at pair " << i << "\n  input  " << describe(requests[i])
                    << "\n  golden " << describe(expected[i]) << "\n  " << who << " " << describe(actual[i]);
    }
  }
  EXPECT_EQ(mismatches, 0u) << who << ": pairs whose result differs from golden";
}

std::string optionsText(const StreamOptions& o) {
  return fmt::format("stall {} idle {} seed {}", o.outputStallProbability, o.inputIdleProbability, o.seed);
}

// ---- Each implementation against the golden model ---------------------------

class ScIsect : public ::testing::TestWithParam<Impl> {
 protected:
  void SetUp() override {
    if (GetParam() == Impl::Rtl && !SystemCIsectDevice::rtlAvailable()) {
      GTEST_SKIP() << "this build has no Verilated RTL (LANCER_RTL_ISECT_SOURCES)";
    }
  }
};

std::string implName(const ::testing::TestParamInfo<Impl>& info) {
  switch (info.param) {
    case Impl::Model: return "Model";
    case Impl::Pins: return "Pins";
    case Impl::Rtl: return "Rtl";
  }
  return "Unknown";
}

INSTANTIATE_TEST_SUITE_P(Impl, ScIsect, ::testing::Values(Impl::Model, Impl::Pins, Impl::Rtl), implName);

TEST_P(ScIsect, MatchesGoldenOnRandomPairsUnderBackpressure) {
  const auto requests = sctest::randomPairs(4000, 11);
  const auto expected = golden(requests);
  SystemCIsectDevice device(GetParam());
  for (const StreamOptions& options : {StreamOptions{0.0, 0.0, 1, {}}, StreamOptions{0.3, 0.2, 2, {}},
                                       StreamOptions{0.8, 0.5, 3, {}}, StreamOptions{0.1, 0.9, 4, {}}}) {
    SCOPED_TRACE(optionsText(options));
    std::vector<fx::IsectResult> results;
    const StreamStats stats = device.run(requests, results, options);
    expectSameResults(requests, expected, results, device.name());
    EXPECT_EQ(stats.requests, requests.size());
    EXPECT_EQ(stats.results, requests.size());
    EXPECT_TRUE(stats.cycleAccurate);
    EXPECT_GE(stats.cycles, requests.size() + kLatency);
  }
}

TEST_P(ScIsect, MatchesGoldenOnHardCases) {
  if (2 * fx::kDirMax > fx::kPosMax) GTEST_SKIP() << "the hard cases need kPosMax >= 2 kDirMax";
  const sctest::HardCases hard = sctest::hardCases();
  const auto expected = golden(hard.pairs);
  // The stimulus is what it claims: every ray through the closed mesh hits it.
  std::set<uint32_t> hitRays;
  for (const fx::IsectResult& r : expected)
    if (r.hit) hitRays.insert(r.rayId);
  for (uint32_t id : hard.meshRays) ASSERT_TRUE(hitRays.count(id)) << "mesh ray " << id << " leaked";

  SystemCIsectDevice device(GetParam());
  std::vector<fx::IsectResult> results;
  const StreamOptions options{0.25, 0.1, 7, {}};
  device.run(hard.pairs, results, options);
  expectSameResults(hard.pairs, expected, results, device.name());
}

TEST_P(ScIsect, SaturatedStreamSustainsOneResultPerCycle) {
  const auto requests = sctest::randomPairs(20000, 5);
  SystemCIsectDevice device(GetParam());
  std::vector<fx::IsectResult> results;
  const StreamStats stats = device.run(requests, results);
  EXPECT_EQ(stats.cycles, requests.size() + kLatency);  // the golden device's ideal count
  EXPECT_EQ(stats.inputStalls, 0u);
  const double perCycle = double(stats.results) / double(stats.cycles);
  EXPECT_GE(perCycle, 0.99) << stats.results << " results in " << stats.cycles << " cycles";
}

// A run of a new device of `impl` with its port trace.
StreamStats runTraced(SystemCIsectDevice::Impl impl, const std::vector<IsectRequest>& requests,
                      std::vector<IsectCycle>& trace, const StreamOptions& options = {}) {
  SystemCIsectDevice device(impl);
  device.setCycleTrace(&trace);
  std::vector<fx::IsectResult> results;
  return device.run(requests, results, options);
}

TEST_P(ScIsect, LatencyIsIsectLatencyCycles) {
  std::vector<IsectCycle> trace;
  const StreamStats stats = runTraced(GetParam(), sctest::randomPairs(1, 3), trace);
  EXPECT_EQ(stats.cycles, kLatency + 1);
  uint64_t accepted = ~uint64_t(0), taken = ~uint64_t(0);
  for (const IsectCycle& c : trace) {
    if (c.reqValid && c.reqReady) accepted = c.cycle;
    if (c.resValid && c.resReady) taken = c.cycle;
  }
  EXPECT_EQ(taken - accepted, kLatency);
}

// The handshake rules and the RTL's backpressure scheme, read off the ports.
TEST_P(ScIsect, HandshakeFollowsTheStreamRulesAndTheRtlBackpressure) {
  const auto requests = sctest::randomPairs(3000, 8);
  std::vector<IsectCycle> trace;
  runTraced(GetParam(), requests, trace, StreamOptions{0.6, 0.3, 9, {}});
  ASSERT_FALSE(trace.empty());
  uint64_t inFlight = 0;  // accepted and not yet taken, at the start of the cycle
  size_t nextResult = 0;
  for (size_t i = 0; i < trace.size(); ++i) {
    const IsectCycle& c = trace[i];
    SCOPED_TRACE(fmt::format("cycle {}", c.cycle));
    // Stage s loads when empty or when s+1 loads: ready is low only when all
    // ISECT_LATENCY stages hold an item and the result is not taken.
    ASSERT_EQ(c.reqReady, !(inFlight == kLatency && !c.resReady));
    ASSERT_LE(inFlight, kLatency);
    if (c.resValid && !c.resReady && i + 1 < trace.size()) {
      ASSERT_TRUE(trace[i + 1].resValid) << "a result was withdrawn";
      ASSERT_EQ(trace[i + 1].resData, c.resData) << "a result changed while stalled";
    }
    if (c.resValid && c.resReady) {
      ASSERT_LT(nextResult, requests.size());
      EXPECT_EQ(fx::unpackResult(c.resData).rayId, requests[nextResult].ray.id) << "out of order";
      ++nextResult;
      --inFlight;
    }
    if (c.reqValid && c.reqReady) ++inFlight;
  }
  EXPECT_EQ(nextResult, requests.size());
  EXPECT_EQ(inFlight, 0u);
}

TEST_P(ScIsect, RepeatedRunsAreIndependentAndReproducible) {
  const auto first = sctest::randomPairs(500, 21);
  const auto second = sctest::randomPairs(777, 22);
  const StreamOptions options{0.4, 0.2, 99, {}};
  std::vector<fx::IsectResult> a, b, c;
  StreamStats sa, sc;
  {
    SystemCIsectDevice device(GetParam());
    sa = device.run(first, a, options);
    device.run(second, b, StreamOptions{0.7, 0.0, 5, {}});
    sc = device.run(first, c, options);
  }
  EXPECT_EQ(a, c);
  EXPECT_EQ(sa.cycles, sc.cycles);
  EXPECT_EQ(sa.inputStalls, sc.inputStalls);
  expectSameResults(second, golden(second), b, "second run");
  // A new device object in the same process (the system is elaborated once).
  SystemCIsectDevice again(GetParam());
  std::vector<fx::IsectResult> d(3);  // results are appended
  const StreamStats sd = again.run(first, d, options);
  ASSERT_EQ(d.size(), first.size() + 3);
  EXPECT_EQ(std::vector<fx::IsectResult>(d.begin() + 3, d.end()), a);
  EXPECT_EQ(sd.cycles, sa.cycles);
}

TEST_P(ScIsect, EmptyRunAndInvalidOptions) {
  SystemCIsectDevice device(GetParam());
  std::vector<fx::IsectResult> results;
  const StreamStats stats = device.run({}, results);
  EXPECT_EQ(stats.cycles, 0u);
  EXPECT_EQ(stats.results, 0u);
  EXPECT_TRUE(results.empty());
  const auto requests = sctest::randomPairs(4, 1);
  EXPECT_THROW(device.run(requests, results, StreamOptions{1.0, 0.0, 1, {}}), std::invalid_argument);
  EXPECT_THROW(device.run(requests, results, StreamOptions{0.0, -0.1, 1, {}}), std::invalid_argument);
  EXPECT_TRUE(results.empty());
  device.run(requests, results);  // still usable
  EXPECT_EQ(results.size(), requests.size());
}

// ---- The implementations against each other ----------------------------------

// Runs `a` and `b` on the same stimulus and stall patterns and expects the same
// ports at every rising edge, the same stats and the same results.
void expectSameCycles(Impl a, Impl b) {
  const auto requests = sctest::randomPairs(2500, 31);
  SystemCIsectDevice first(a), second(b);
  for (const StreamOptions& options :
       {StreamOptions{0.0, 0.0, 1, {}}, StreamOptions{0.5, 0.0, 2, {}}, StreamOptions{0.0, 0.5, 3, {}},
        StreamOptions{0.3, 0.3, 4, {}}, StreamOptions{0.9, 0.1, 5, {}}, StreamOptions{0.05, 0.95, 6, {}}}) {
    SCOPED_TRACE(optionsText(options));
    std::vector<IsectCycle> firstTrace, secondTrace;
    first.setCycleTrace(&firstTrace);
    second.setCycleTrace(&secondTrace);
    std::vector<fx::IsectResult> firstResults, secondResults;
    const StreamStats f = first.run(requests, firstResults, options);
    const StreamStats s = second.run(requests, secondResults, options);
    EXPECT_EQ(f.cycles, s.cycles);
    EXPECT_EQ(f.requests, s.requests);
    EXPECT_EQ(f.results, s.results);
    EXPECT_EQ(f.inputStalls, s.inputStalls);
    EXPECT_EQ(firstResults, secondResults);
    ASSERT_EQ(firstTrace.size(), secondTrace.size());
    for (size_t i = 0; i < firstTrace.size(); ++i) {
      ASSERT_EQ(firstTrace[i], secondTrace[i])
          << "first difference between " << first.name() << " (a) and " << second.name() << " (b)";
    }
  }
}

// The cycle model, on value ports and on pins, is meant to be interchangeable
// with the RTL: the same ports, sampled at every rising edge.
class ScModelCycleAccuracy : public ::testing::TestWithParam<Impl> {};

INSTANTIATE_TEST_SUITE_P(Impl, ScModelCycleAccuracy, ::testing::Values(Impl::Model, Impl::Pins), implName);

TEST_P(ScModelCycleAccuracy, MatchesVerilatedRtlCycleForCycle) {
  if (!SystemCIsectDevice::rtlAvailable()) GTEST_SKIP() << "no Verilated RTL in this build";
  expectSameCycles(GetParam(), Impl::Rtl);
}

// Without the RTL too: the run loop's stimulus and sampling are the testbench's.
TEST(ScCycleAccuracy, ValuePortsMatchPinsCycleForCycle) { expectSameCycles(Impl::Model, Impl::Pins); }

// Every cycle-accurate device draws the same stimulus from the same options, so
// the SystemC devices report what the C++ Verilated device ("rtl") reports.
TEST(ScCycleAccuracy, StatsEqualTheCxxVerilatedDevice) {
  const auto requests = sctest::randomPairs(1500, 41);
  VerilatorIsectDevice cxx;
  std::vector<SystemCIsectDevice> devices;
  devices.emplace_back(Impl::Model);
  devices.emplace_back(Impl::Pins);
  if (SystemCIsectDevice::rtlAvailable()) devices.emplace_back(Impl::Rtl);
  for (const StreamOptions& options :
       {StreamOptions{0.0, 0.0, 1, {}}, StreamOptions{0.4, 0.3, 12, {}}, StreamOptions{0.85, 0.6, 13, {}}}) {
    SCOPED_TRACE(optionsText(options));
    std::vector<fx::IsectResult> expected;
    const StreamStats want = cxx.run(requests, expected, options);
    for (SystemCIsectDevice& device : devices) {
      std::vector<fx::IsectResult> results;
      sctest::expectSameStats(device.run(requests, results, options), want, device.name());
      EXPECT_EQ(results, expected) << device.name();
    }
  }
}

TEST(ScDevice, AllImplementationsInterleaveInOneProcess) {
  if (!SystemCIsectDevice::rtlAvailable()) GTEST_SKIP() << "no Verilated RTL in this build";
  for (int round = 0; round < 4; ++round) {
    const auto requests = sctest::randomPairs(100 + 150 * size_t(round), 50 + uint64_t(round));
    const auto expected = golden(requests);
    for (const Impl impl : {Impl::Rtl, Impl::Model, Impl::Pins}) {
      SystemCIsectDevice device(impl);  // constructed anew every time
      std::vector<fx::IsectResult> results;
      device.run(requests, results, StreamOptions{0.2 * round, 0.1, uint64_t(round), {}});
      expectSameResults(requests, expected, results, device.name());
    }
  }
}

TEST(ScDevice, NamesAndAvailability) {
  EXPECT_EQ(SystemCIsectDevice(Impl::Model).name(), "systemc");
  EXPECT_EQ(SystemCIsectDevice(Impl::Pins).name(), "systemc-pins");
  if (SystemCIsectDevice::rtlAvailable()) {
    EXPECT_EQ(SystemCIsectDevice(Impl::Rtl).name(), "rtl-systemc");
  } else {
    EXPECT_THROW(SystemCIsectDevice{Impl::Rtl}, std::runtime_error);
  }
}

TEST(ScDevice, WaveformsOfTheRtlOnRequest) {
  const auto requests = sctest::randomPairs(50, 61);
  const auto dir = std::filesystem::path(::testing::TempDir()) / "lancer_sc_waves";
  std::filesystem::create_directories(dir);
  // The cycle model has no RTL signals: it ignores the option, as golden does.
  for (const Impl impl : {Impl::Model, Impl::Pins}) {
    SystemCIsectDevice model(impl);
    std::vector<fx::IsectResult> results;
    StreamOptions options;
    options.wavePath = (dir / fmt::format("{}.fst", model.name())).string();
    model.run(requests, results, options);
    EXPECT_EQ(results, golden(requests));
    EXPECT_FALSE(std::filesystem::exists(options.wavePath));
  }
  if (!SystemCIsectDevice::rtlAvailable()) GTEST_SKIP() << "no Verilated RTL in this build";
  SystemCIsectDevice rtl(Impl::Rtl);
  if (!SystemCIsectDevice::wavesAvailable()) {
    std::vector<fx::IsectResult> results;
    EXPECT_THROW(rtl.run(requests, results, StreamOptions{0, 0, 1, (dir / "x.fst").string()}),
                 std::runtime_error);
    return;
  }
  for (const char* name : {"first.fst", "second.fst"}) {  // one file per run
    const auto path = dir / name;
    std::filesystem::remove(path);
    std::vector<fx::IsectResult> results;
    rtl.run(requests, results, StreamOptions{0.3, 0.0, 1, path.string()});
    EXPECT_EQ(results, golden(requests));
    ASSERT_TRUE(std::filesystem::exists(path));
    EXPECT_GT(std::filesystem::file_size(path), 100u);
  }
  std::vector<fx::IsectResult> results;
  rtl.run(requests, results);  // and none afterwards
  EXPECT_EQ(results, golden(requests));
}

}  // namespace
}  // namespace lancer
