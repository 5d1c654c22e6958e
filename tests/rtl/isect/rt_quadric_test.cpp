// Tests of the quadric pipeline rtl/isect/rt_quadric.sv, Verilated, and of its
// cycle model systemc/isect/rt_quadric_model: bit-identical results to the
// golden model (fx::intersectQuadric) in the same order, on random sphere and
// cone pairs and the hard cases, with and without backpressure and input
// bubbles; the cycle model's ports equal to the RTL's cycle for cycle; the port
// timing (latency rt_pkg::QUADRIC_LATENCY, one result per cycle); the live SVA
// assertions (a failure throws from the run loop).

#include <gtest/gtest.h>

#include <span>
#include <string>
#include <vector>


#include "Vrt_quadric.h"
#include "driver/isect_run.h"
#include "driver/model_unit.h"
#include "driver/report.h"
#include "driver/verilated_unit.h"
#include "golden/quadric.h"
#include "isect/isect_cases.h"
#include "isect/quadric_cases.h"
#include "isect/rt_quadric_model.h"

namespace lancer {
namespace {

using fx::IsectResult;
using rtltest::backpressure;
using rtltest::QuadricCaseGroup;

struct RtlQuadric : VerilatedUnit<Vrt_quadric> {
  RtlQuadric() : VerilatedUnit<Vrt_quadric>("rt_quadric") { reset(isect_detail::idleInputs<Vrt_quadric>); }
};
struct ModelQuadric : ModelUnit<sc::rt_quadric_model> {
  ModelQuadric() { reset(isect_detail::idleInputs<sc::rt_quadric_model>); }
};

std::string describe(const QuadricRequest& req) { return hexFields(req.ray) + "; " + hexFields(req.quadric); }

// The results of `requests` through a clocked model, against the golden model,
// in order; the first few differences with their inputs.
template <class Clocked>
StreamStats expectGolden(Clocked& unit, std::span<const QuadricRequest> requests, const StreamOptions& options,
                         std::string_view who) {
  std::vector<IsectResult> results;
  const StreamStats stats = runIsectStream(unit, requests, results, options);
  EXPECT_EQ(results.size(), requests.size()) << who;
  size_t mismatches = 0;
  for (size_t i = 0; i < std::min(results.size(), requests.size()); ++i) {
    const IsectResult expected = fx::intersectQuadric(requests[i].ray, requests[i].quadric);
    if (results[i] == expected) continue;
    if (++mismatches <= 5) {
      ADD_FAILURE() << who << " differs from golden at pair " << i << "\n  input  " << describe(requests[i])
                    << "\n  golden " << hexFields(expected) << "\n  " << who << " " << hexFields(results[i]);
    }
  }
  EXPECT_EQ(mismatches, 0u) << who;
  return stats;
}

std::vector<QuadricRequest> hardPairs() {
  std::vector<QuadricRequest> all;
  for (const QuadricCaseGroup& g : rtltest::quadricHardCases()) all.insert(all.end(), g.pairs.begin(), g.pairs.end());
  return all;
}

TEST(RtQuadric, RandomPairsMatchGoldenBitForBit) {
  const auto pairs = rtltest::randomQuadricPairs(20000, 7);
  size_t hits = 0, leaving = 0;
  for (const QuadricRequest& p : pairs) {
    const IsectResult r = fx::intersectQuadric(p.ray, p.quadric);
    hits += r.hit;
    leaving += r.hit && r.uNum == 1;
  }
  EXPECT_GT(hits, pairs.size() / 5) << "the stimulus must hit often";
  EXPECT_GT(leaving, 50u);
  RtlQuadric rtl;
  expectGolden(rtl, std::span<const QuadricRequest>(pairs), {}, "rtl");
  expectGolden(rtl, std::span<const QuadricRequest>(pairs), backpressure(0.3, 0.2, 11), "rtl (stalls, bubbles)");
}

TEST(RtQuadric, HardCasesMatchGoldenBitForBit) {
  RtlQuadric rtl;
  for (const QuadricCaseGroup& g : rtltest::quadricHardCases()) {
    SCOPED_TRACE(g.name);
    ASSERT_FALSE(g.pairs.empty());
    expectGolden(rtl, std::span<const QuadricRequest>(g.pairs), backpressure(0.25, 0.25, 3), "rtl");
  }
  // The groups reach both verdicts.
  size_t hits = 0;
  const auto all = hardPairs();
  for (const QuadricRequest& p : all) hits += fx::intersectQuadric(p.ray, p.quadric).hit;
  EXPECT_GT(hits, 10u);
  EXPECT_LT(hits, all.size() - 10);
}

TEST(RtQuadric, LatencyAndOneResultPerCycle) {
  const auto pairs = rtltest::randomQuadricPairs(500, 5);
  RtlQuadric rtl;
  std::vector<IsectResult> results;
  const auto one = std::span<const QuadricRequest>(pairs).first(1);
  // The run's cycles count the cycle the request is offered and accepted in
  // and the one its result is taken in (as rt_isect's: 1 + latency).
  EXPECT_EQ(runIsectStream(rtl, one, results, {}).cycles, 1u + fx::kQuadricLatency);
  // A stream without stalls: one result a cycle after the first.
  const StreamStats stats = runIsectStream(rtl, std::span<const QuadricRequest>(pairs), results, {});
  EXPECT_EQ(stats.cycles, pairs.size() + fx::kQuadricLatency);
  EXPECT_EQ(stats.inputStalls, 0u);
  // A consumer that stalls: the pipeline fills, then accepts as it drains.
  const StreamStats stalled = runIsectStream(rtl, std::span<const QuadricRequest>(pairs), results, backpressure(0.5, 0.0, 9));
  EXPECT_GT(stalled.inputStalls, 0u);
  EXPECT_EQ(stalled.results, pairs.size());
}

TEST(RtQuadricModel, MatchesGoldenAndTheRtlCycleForCycle) {
  auto pairs = rtltest::randomQuadricPairs(4000, 21);
  const auto hard = hardPairs();
  pairs.insert(pairs.end(), hard.begin(), hard.end());
  ModelQuadric model;
  expectGolden(model, std::span<const QuadricRequest>(pairs), {}, "systemc");
  for (const StreamOptions& options : {StreamOptions{}, backpressure(0.3, 0.2, 13), backpressure(0.9, 0.0, 2)}) {
    RtlQuadric rtl;
    ModelQuadric cycleModel;
    std::vector<IsectResult> a, b;
    std::vector<sc::IsectCycle> rtlTrace, modelTrace;
    runIsectStream(rtl, std::span<const QuadricRequest>(pairs), a, options, &rtlTrace);
    runIsectStream(cycleModel, std::span<const QuadricRequest>(pairs), b, options, &modelTrace);
    ASSERT_EQ(rtlTrace.size(), modelTrace.size()) << "stall " << options.outputStallProbability;
    for (size_t c = 0; c < rtlTrace.size(); ++c) {
      ASSERT_EQ(rtlTrace[c], modelTrace[c]) << "cycle " << c << ", stall " << options.outputStallProbability;
    }
    EXPECT_EQ(a, b);
  }
}

}  // namespace
}  // namespace lancer
