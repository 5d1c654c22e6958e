// The SystemC side of rt_quadric, the quadric pipeline beside rt_isect: its
// cycle model on value ports ("systemc"), on pins in the kernel
// ("systemc-pins") and the Verilated RTL in SystemC ("rtl-systemc") against
// the golden model (fx::intersectQuadric), against each other port for port at
// every rising edge, and against the C++ Verilated RTL device ("rtl").
#include <gtest/gtest.h>

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "driver/report.h"
#include "driver/systemc_isect_device.h"
#include "driver/verilator_isect_device.h"
#include "golden/quadric.h"
#include "isect/quadric_cases.h"
#include "isect_stimulus.h"

namespace lancer {
namespace {

using Impl = SystemCIsectDevice::Impl;

// The options the tests stream under: none, output stalls, input bubbles, both.
const std::vector<StreamOptions> kOptions{StreamOptions{0.0, 0.0, 1, {}}, StreamOptions{0.5, 0.0, 2, {}},
                                          StreamOptions{0.0, 0.5, 3, {}}, StreamOptions{0.3, 0.3, 4, {}},
                                          StreamOptions{0.9, 0.1, 5, {}}};

std::string optionsText(const StreamOptions& o) {
  return fmt::format("stall {} idle {} seed {}", o.outputStallProbability, o.inputIdleProbability, o.seed);
}

// Every result equal to golden's, in request order; the first few differences with their inputs.
void expectGolden(std::span<const QuadricRequest> requests, const std::vector<fx::IsectResult>& results,
                  std::string_view who) {
  ASSERT_EQ(results.size(), requests.size()) << who;
  size_t mismatches = 0;
  for (size_t i = 0; i < results.size(); ++i) {
    const fx::IsectResult expected = fx::intersectQuadric(requests[i].ray, requests[i].quadric);
    if (results[i] == expected) continue;
    if (++mismatches <= 5) {
      ADD_FAILURE() << who << " differs from golden at pair " << i << "\n  ray     " << hexFields(requests[i].ray)
                    << "\n  quadric " << hexFields(requests[i].quadric) << "\n  golden  " << hexFields(expected)
                    << "\n  " << who << " " << hexFields(results[i]);
    }
  }
  EXPECT_EQ(mismatches, 0u) << who << ": pairs whose result differs from golden";
}

std::vector<Impl> availableImpls() {
  std::vector<Impl> impls{Impl::Model, Impl::Pins};
  if (SystemCIsectDevice::rtlAvailable()) impls.push_back(Impl::Rtl);
  return impls;
}

TEST(ScQuadric, EveryFormMatchesGoldenOnRandomPairsAndTheHardCases) {
  std::vector<QuadricRequest> requests = rtltest::randomQuadricPairs(1500, 71);
  for (const rtltest::QuadricCaseGroup& g : rtltest::quadricHardCases()) {
    requests.insert(requests.end(), g.pairs.begin(), g.pairs.end());
  }
  for (const Impl impl : availableImpls()) {
    SystemCIsectDevice device(impl);
    for (const StreamOptions& options : kOptions) {
      SCOPED_TRACE(optionsText(options));
      std::vector<fx::IsectResult> results;
      device.runQuadrics(requests, results, options);
      expectGolden(requests, results, device.name());
    }
  }
}

// The three SystemC forms: the same ports at every rising edge, the same stats
// and results; and the stats and results of the C++ Verilated rt_quadric,
// which draws the same stimulus from the same options.
TEST(ScQuadric, EveryFormMatchesTheRtlCycleForCycle) {
  const std::vector<QuadricRequest> requests = rtltest::randomQuadricPairs(1200, 72);
  VerilatorIsectDevice cxx;
  const std::vector<Impl> impls = availableImpls();
  for (const StreamOptions& options : kOptions) {
    SCOPED_TRACE(optionsText(options));
    std::vector<fx::IsectResult> expected;
    const StreamStats want = cxx.runQuadrics(requests, expected, options);
    std::vector<sc::IsectCycle> firstTrace;
    for (const Impl impl : impls) {
      SystemCIsectDevice device(impl);
      std::vector<sc::IsectCycle> trace;
      device.setCycleTrace(&trace);
      std::vector<fx::IsectResult> results;
      sctest::expectSameStats(device.runQuadrics(requests, results, options), want, device.name());
      EXPECT_EQ(results, expected) << device.name();
      if (impl == impls.front()) {
        firstTrace = std::move(trace);
        continue;
      }
      ASSERT_EQ(trace.size(), firstTrace.size()) << device.name();
      for (size_t i = 0; i < trace.size(); ++i) {
        ASSERT_TRUE(trace[i] == firstTrace[i]) << "cycle " << i << ": " << device.name() << " differs from systemc";
      }
    }
  }
}

// Triangles and quadrics interleave on one device, each on its own pipeline.
TEST(ScQuadric, TrianglesAndQuadricsInterleaveOnOneDevice) {
  const std::vector<QuadricRequest> quadrics = rtltest::randomQuadricPairs(300, 73);
  for (const Impl impl : availableImpls()) {
    SystemCIsectDevice device(impl);
    for (int round = 0; round < 3; ++round) {
      std::vector<fx::IsectResult> results;
      device.runQuadrics(quadrics, results, StreamOptions{0.2 * round, 0.1, uint64_t(round), {}});
      expectGolden(quadrics, results, device.name());
      std::vector<fx::IsectResult> none;
      device.run({}, none);
      EXPECT_TRUE(none.empty());
    }
  }
}

// rtl-systemc writes rt_quadric's waveform beside rt_isect's: x.fst gives x.quadric.fst.
TEST(ScQuadric, WaveformOfTheRtlBesideTheTriangles) {
  if (!SystemCIsectDevice::rtlAvailable() || !SystemCIsectDevice::wavesAvailable()) {
    GTEST_SKIP() << "no Verilated RTL with FST tracing in this build";
  }
  const std::vector<QuadricRequest> requests = rtltest::randomQuadricPairs(40, 74);
  const auto dir = std::filesystem::path(::testing::TempDir()) / "lancer_sc_quadric_waves";
  std::filesystem::create_directories(dir);
  std::filesystem::remove(dir / "q.quadric.fst");
  SystemCIsectDevice rtl(Impl::Rtl);
  std::vector<fx::IsectResult> results;
  rtl.runQuadrics(requests, results, StreamOptions{0.3, 0.0, 1, (dir / "q.fst").string()});
  expectGolden(requests, results, rtl.name());
  ASSERT_TRUE(std::filesystem::exists(dir / "q.quadric.fst"));
  EXPECT_GT(std::filesystem::file_size(dir / "q.quadric.fst"), 100u);
  EXPECT_FALSE(std::filesystem::exists(dir / "q.fst"));
}

}  // namespace
}  // namespace lancer
