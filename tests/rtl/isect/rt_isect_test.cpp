// Tests of the RTL intersection pipeline rtl/isect/rt_isect.sv, Verilated:
// bit-identical results to the golden model in the same order, under random
// backpressure and input bubbles, on random pairs and the hard corners; the
// watertightness of the fixed-point test on a closed mesh; the port timing
// (latency, capacity, one result per cycle); the live SVA assertions.
//
// A mismatch prints a reproducer: the request as hex wire images, both results,
// the differing bits, and a command replaying just that pair (RtIsect.Replay).

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <type_traits>
#include <filesystem>
#include <string>

#include <fmt/format.h>

#include "Vrt_isect.h"
#include "driver/golden_device.h"
#include "driver/verilator_isect_device.h"
#include "golden/isect.h"
#include "isect/isect_cases.h"
#include "verilated.h"

namespace lancer {
namespace {

using fx::IsectResult;
using fx::u128;
using rtltest::backpressure;

std::string hex(const fx::Wire& wire) {
  std::string s;
  for (size_t i = wire.size(); i-- > 0;) s += fmt::format("{:08x}", wire[i]);
  return s;
}

fx::Wire fromHex(const std::string& text, size_t words) {
  fx::Wire wire(words, 0);
  size_t word = 0;
  for (size_t end = text.size(); end > 0 && word < words; ++word) {
    const size_t begin = end >= 8 ? end - 8 : 0;
    wire[word] = uint32_t(std::stoul(text.substr(begin, end - begin), nullptr, 16));
    end = begin;
  }
  return wire;
}

std::string u128Hex(u128 v) {
  if (v >> 64) return fmt::format("{:x}{:016x}", uint64_t(v >> 64), uint64_t(v));
  return fmt::format("{:x}", uint64_t(v));
}

std::string describe(const IsectResult& r) {
  return fmt::format("hit={} t_num=0x{} det=0x{} u_num=0x{} v_num=0x{} ray={} prim={}", r.hit,
                     u128Hex(r.tNum), u128Hex(r.det), u128Hex(r.uNum), u128Hex(r.vNum), r.rayId,
                     r.primId);
}

std::string reproducer(const IsectRequest& req, const IsectResult& rtl, const IsectResult& golden) {
  const fx::Wire rayWire = fx::packWire(req.ray), triWire = fx::packWire(req.tri);
  const fx::Wire a = fx::packWire(rtl), b = fx::packWire(golden);
  fx::Wire diff(a.size());
  for (size_t i = 0; i < a.size(); ++i) diff[i] = a[i] ^ b[i];
  const auto& o = req.ray.org;
  const auto& d = req.ray.dir;
  const auto& v = req.tri.v;
  return fmt::format(
      "  ray {} org ({}, {}, {}) dir ({}, {}, {}); tri {} v0 ({}, {}, {}) v1 ({}, {}, {}) v2 ({}, {}, {})\n"
      "  ray wire {}\n  tri wire {}\n  rtl    {}\n  golden {}\n  xor wire {}\n"
      "  replay: LANCER_RTL_REPLAY={},{} {} --gtest_filter=RtIsect.Replay\n",
      req.ray.id, o[0], o[1], o[2], d[0], d[1], d[2], req.tri.id, v[0][0], v[0][1], v[0][2],
      v[1][0], v[1][1], v[1][2], v[2][0], v[2][1], v[2][2], hex(rayWire), hex(triWire),
      describe(rtl), describe(golden), hex(diff), hex(rayWire), hex(triWire),
      ::testing::internal::GetArgvs().front());
}

// Streams `requests` through the RTL (with `options`) and the golden device and
// requires the same results, bit for bit, in the same order.
StreamStats expectBitIdentical(std::span<const IsectRequest> requests, const StreamOptions& options,
                               std::vector<IsectResult>* rtlOut = nullptr) {
  VerilatorIsectDevice rtl;
  GoldenIsectDevice golden;
  std::vector<IsectResult> got, want;
  const StreamStats stats = rtl.run(requests, got, options);
  golden.run(requests, want);
  EXPECT_EQ(stats.requests, requests.size());
  EXPECT_EQ(stats.results, requests.size());
  EXPECT_EQ(got.size(), want.size());
  size_t mismatches = 0;
  for (size_t i = 0; i < std::min(got.size(), want.size()); ++i) {
    if (got[i] == want[i]) continue;
    if (++mismatches <= 5) {
      ADD_FAILURE() << "result " << i << " differs from the golden model\n"
                    << reproducer(requests[i], got[i], want[i]);
    }
  }
  EXPECT_EQ(mismatches, 0u) << "of " << requests.size() << " results";
  if (rtlOut) *rtlOut = std::move(got);
  return stats;
}


size_t hits(const std::vector<IsectResult>& results) {
  return size_t(std::count_if(results.begin(), results.end(), [](const auto& r) { return r.hit; }));
}

// ---- Bit identity -------------------------------------------------------------

TEST(RtIsect, RandomPairsMatchGolden) {
  const auto pairs = rtltest::randomPairs(500000, 11);
  std::vector<IsectResult> results;
  expectBitIdentical(pairs, {}, &results);
  // The mix must exercise both outcomes.
  EXPECT_GT(hits(results), pairs.size() / 5);
  EXPECT_LT(hits(results), pairs.size() * 4 / 5);
}

TEST(RtIsect, RandomPairsUnderBackpressureMatchGolden) {
  const auto pairs = rtltest::randomPairs(30000, 12);
  for (const auto& [stall, idle] : {std::pair{0.3, 0.0}, {0.0, 0.3}, {0.3, 0.2}, {0.9, 0.5}}) {
    SCOPED_TRACE(fmt::format("stall {} idle {}", stall, idle));
    const StreamStats stats = expectBitIdentical(pairs, backpressure(stall, idle, 99));
    EXPECT_GE(stats.cycles, pairs.size() + fx::kIsectLatency);
  }
}

class RtIsectHardCases : public ::testing::TestWithParam<std::string> {};

TEST_P(RtIsectHardCases, MatchGoldenUnderBackpressure) {
  for (auto& group : rtltest::hardCases(7)) {
    if (group.name != GetParam()) continue;
    ASSERT_FALSE(group.pairs.empty());
    std::vector<IsectResult> results;
    expectBitIdentical(group.pairs, backpressure(0.3, 0.1, 5), &results);
    RecordProperty("pairs", int(group.pairs.size()));
    RecordProperty("hits", int(hits(results)));
    if (group.name == "degenerate") {  // zero area: det == 0, never a hit
      EXPECT_EQ(hits(results), 0u);
    } else if (group.name == "needle" || group.name == "tiny_dirs" || group.name == "axis_ties" ||
               group.name == "triangle_ties" || group.name == "extremes") {
      EXPECT_GT(hits(results), 0u) << "the group must exercise hits";
    } else if (group.name == "segment_ends") {  // ends at, past and short of the hits
      EXPECT_GT(hits(results), group.pairs.size() / 5);
      EXPECT_LT(hits(results), group.pairs.size() * 4 / 5);
    }
    if (group.name == "extremes") {
      // The corner cases must reach the top bits of every output field.
      auto bits = [](u128 v) { int n = 0; while (v) ++n, v >>= 1; return n; };
      int tBits = 0, detBits = 0, uBits = 0;
      for (const auto& r : results) {
        tBits = std::max(tBits, bits(r.tNum));
        detBits = std::max(detBits, bits(r.det));
        uBits = std::max({uBits, bits(r.uNum), bits(r.vNum)});
      }
      RecordProperty("t_num_bits", tBits);
      RecordProperty("det_bits", detBits);
      RecordProperty("bary_bits", uBits);
      // The format bounds are sums of worst cases that one hit cannot reach
      // together (T: three products of the largest edge and depth); the corners
      // come within a few bits of each.
      std::printf("extremes: t_num %d of %d bits, det %d of %d, u/v %d of %d\n", tBits,
                  fx::kTNumBits, detBits, fx::kDetAbsBits, uBits, fx::kBaryBits);
      EXPECT_GE(tBits, fx::kTNumBits - 4);
      EXPECT_GE(detBits, fx::kDetAbsBits - 3);
      EXPECT_GE(uBits, fx::kBaryBits - 3);
    }
    return;
  }
  FAIL() << "no group " << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Groups, RtIsectHardCases,
                         ::testing::Values("degenerate", "needle", "parallel", "tiny_dirs",
                                           "axis_ties", "triangle_ties", "extremes", "segment_ends"),
                         [](const auto& info) { return info.param; });

// Every ray aimed at a vertex or an edge point of a closed mesh, or leaving its
// interior, hits at least one face: no ray leaks through a shared edge or vertex
// in the fixed-point domain. `pairs` holds each ray with all `faces` faces.
void expectWatertight(const std::vector<IsectRequest>& pairs, size_t faces) {
  ASSERT_EQ(pairs.size() % faces, 0u);
  std::vector<IsectResult> results;
  expectBitIdentical(pairs, backpressure(0.3, 0.2, 8), &results);
  ASSERT_EQ(results.size(), pairs.size());
  size_t leaks = 0;
  for (size_t r = 0; r < pairs.size() / faces; ++r) {
    bool hit = false;
    for (size_t f = 0; f < faces; ++f) hit |= results[r * faces + f].hit;
    if (!hit && ++leaks <= 5) {
      const auto& ray = pairs[r * faces].ray;
      ADD_FAILURE() << fmt::format("ray {} leaks: org ({}, {}, {}) dir ({}, {}, {})", ray.id,
                                   ray.org[0], ray.org[1], ray.org[2], ray.dir[0], ray.dir[1],
                                   ray.dir[2]);
    }
  }
  EXPECT_EQ(leaks, 0u) << "of " << pairs.size() / faces << " rays";
}

TEST(RtIsect, WatertightOnClosedOctahedron) {
  expectWatertight(rtltest::watertightRays(20000, 21), rtltest::kOctahedronFaces);
}

TEST(RtIsect, WatertightOnClosedTetrahedra) {
  expectWatertight(rtltest::watertightTetraRays(40000, 22), rtltest::kTetraFaces);
}

// ---- Timing -------------------------------------------------------------------

TEST(RtIsect, SaturatedStreamSustainsOneResultPerCycle) {
  const auto pairs = rtltest::randomPairs(100000, 31);
  const StreamStats stats = expectBitIdentical(pairs, {});
  EXPECT_TRUE(stats.cycleAccurate);
  EXPECT_EQ(stats.inputStalls, 0u);
  EXPECT_EQ(stats.cycles, pairs.size() + fx::kIsectLatency);
  const double perCycle = double(stats.results) / double(stats.cycles);
  RecordProperty("results_per_cycle", fmt::format("{:.5f}", perCycle));
  EXPECT_GE(perCycle, 0.99);
}

TEST(RtIsect, OneRequestTakesIsectLatencyCycles) {
  const auto pairs = rtltest::randomPairs(1, 1);
  const StreamStats stats = expectBitIdentical(pairs, {});
  // Offered and accepted in cycle 0, taken in cycle ISECT_LATENCY.
  EXPECT_EQ(stats.cycles, 1u + fx::kIsectLatency);
}

TEST(RtIsect, RepeatedRunsAndWaveform) {
  const auto pairs = rtltest::randomPairs(300, 41);
  VerilatorIsectDevice rtl;
  GoldenIsectDevice golden;
  std::vector<IsectResult> want;
  golden.run(pairs, want);
  const auto wave = std::filesystem::path(::testing::TempDir()) / "rt_isect_test.fst";
  std::filesystem::remove(wave);
  for (int run = 0; run < 3; ++run) {
    StreamOptions options = backpressure(0.2, 0.2, uint64_t(run));
    if (run == 1) options.wavePath = wave.string();
    std::vector<IsectResult> got;
    rtl.run(pairs, got, options);
    EXPECT_EQ(got, want) << "run " << run;
  }
  ASSERT_TRUE(std::filesystem::exists(wave));
  EXPECT_GT(std::filesystem::file_size(wave), 1000u);
}

// A record's words into or out of a Verilated port (an integer up to 64 bits,
// else a VlWide of 32-bit words in the same order as fx::Wire).
template <typename Port>
void toPort(Port& port, const fx::Wire& wire) {
  if constexpr (std::is_integral_v<Port>) {
    port = Port(wire.size() > 1 ? (uint64_t(wire[1]) << 32 | wire[0]) : wire[0]);
  } else {
    std::memcpy(port.data(), wire.data(), wire.size() * sizeof(uint32_t));
  }
}
template <typename Port>
fx::Wire fromPort(const Port& port, size_t words) {
  fx::Wire wire(words, 0);
  if constexpr (std::is_integral_v<Port>) {
    wire[0] = uint32_t(uint64_t(port));
    if (words > 1) wire[1] = uint32_t(uint64_t(port) >> 32);
  } else {
    std::memcpy(wire.data(), port.data(), words * sizeof(uint32_t));
  }
  return wire;
}

// Drives the Verilated ports directly, one edge at a time.
class Ports {
 public:
  Ports() : top_(&context_, "rt_isect") {
    context_.fatalOnError(false);
    top_.rst_ni = 0;
    top_.clk_i = 0;
    top_.eval();
    tick();
    top_.rst_ni = 1;
    top_.eval();
  }
  ~Ports() { top_.final(); }
  // Offers `r` (req_valid_i high) and settles the combinational outputs.
  void offer(const IsectRequest& r) {
    toPort(top_.req_ray_i, fx::packWire(r.ray));
    toPort(top_.req_tri_i, fx::packWire(r.tri));
    top_.req_valid_i = 1;
    top_.eval();
  }
  void tick() {
    top_.clk_i = 1;
    top_.eval();
    top_.clk_i = 0;
    top_.eval();
  }
  fx::Wire result() const {
    return fromPort(top_.res_data_o, size_t(fx::wireWords(fx::kIsectResBits)));
  }
  VerilatedContext context_;
  Vrt_isect top_;
};

TEST(RtIsectPorts, LatencyIsExactlyIsectLatency) {
  Ports p;
  const auto pairs = rtltest::randomPairs(1, 3);
  p.offer(pairs[0]);
  p.top_.res_ready_i = 1;
  p.top_.eval();
  ASSERT_TRUE(p.top_.req_ready_o);
  EXPECT_FALSE(p.top_.res_valid_o);
  p.tick();  // the accepting edge
  p.top_.req_valid_i = 0;
  p.top_.eval();
  // res_valid_o rises after edge ISECT_LATENCY - 1 and is sampled by the
  // consumer at edge ISECT_LATENCY after the accepting one.
  int edges = 0;
  while (!p.top_.res_valid_o && edges < 100) {
    p.tick();
    ++edges;
  }
  EXPECT_EQ(edges + 1, fx::kIsectLatency) << "edges from acceptance to the consumer's sample";
  EXPECT_EQ(fx::unpackResult(p.result()), fx::intersect(pairs[0].ray, pairs[0].tri));
  p.tick();  // taken
  EXPECT_FALSE(p.top_.res_valid_o);
  EXPECT_FALSE(p.context_.gotError());
}

TEST(RtIsectPorts, FullStallHoldsLatencyItemsAndDataThenDrainsAtFullRate) {
  Ports p;
  const auto pairs = rtltest::randomPairs(40, 4);
  p.top_.res_ready_i = 0;
  size_t accepted = 0;
  for (int cycle = 0; cycle < 20; ++cycle) {
    p.offer(pairs[accepted]);
    if (p.top_.req_ready_o) ++accepted;
    p.tick();
  }
  EXPECT_EQ(accepted, size_t(fx::kIsectLatency)) << "one item per stage, then req_ready_o falls";
  p.top_.eval();
  EXPECT_FALSE(p.top_.req_ready_o);
  ASSERT_TRUE(p.top_.res_valid_o);
  const fx::Wire held = p.result();
  p.tick();
  EXPECT_EQ(p.result(), held) << "res_data_o must hold while res_ready_i is low";
  // Now take a result every cycle: one request enters in the same cycle.
  p.top_.res_ready_i = 1;
  size_t taken = 0;
  for (int cycle = 0; cycle < 20; ++cycle) {
    p.offer(pairs[accepted]);
    EXPECT_TRUE(p.top_.req_ready_o) << "cycle " << cycle;
    EXPECT_TRUE(p.top_.res_valid_o) << "cycle " << cycle;
    EXPECT_EQ(fx::unpackResult(p.result()), fx::intersect(pairs[taken].ray, pairs[taken].tri));
    ++accepted, ++taken;
    p.tick();
  }
  EXPECT_FALSE(p.context_.gotError());
}

TEST(RtIsectPorts, AssertionsAreLive) {
  Ports p;
  const auto pairs = rtltest::randomPairs(20, 5);
  // Fill the pipeline with the consumer stalled, then break the producer's
  // rule: withdraw an offered request that was not taken.
  p.top_.res_ready_i = 0;
  for (int cycle = 0; cycle < fx::kIsectLatency; ++cycle) {  // all accepted
    p.offer(pairs[size_t(cycle)]);
    p.tick();
  }
  p.offer(pairs[size_t(fx::kIsectLatency)]);  // refused, and correctly held
  p.tick();
  p.tick();
  EXPECT_FALSE(p.context_.gotError());
  p.top_.req_valid_i = 0;
  testing::internal::CaptureStdout();
  p.tick();
  p.tick();
  const std::string log = testing::internal::GetCapturedStdout();
  EXPECT_TRUE(p.context_.gotError()) << "a_req_hold must fire; is --assert on?";
  EXPECT_NE(log.find("a_req_hold"), std::string::npos) << log;
}

// Replays one pair given as hex wire images (from a mismatch report).
TEST(RtIsect, Replay) {
  const char* env = std::getenv("LANCER_RTL_REPLAY");
  if (!env) GTEST_SKIP() << "set LANCER_RTL_REPLAY=<ray hex>,<tri hex>";
  const std::string text(env);
  const size_t comma = text.find(',');
  ASSERT_NE(comma, std::string::npos);
  const IsectRequest req{
      fx::unpackRay(fromHex(text.substr(0, comma), size_t(fx::wireWords(fx::kIsectRayBits)))),
      fx::unpackTriangle(fromHex(text.substr(comma + 1), size_t(fx::wireWords(fx::kIsectTriBits))))};
  std::vector<IsectRequest> one{req};
  std::vector<IsectResult> got;
  expectBitIdentical(one, {}, &got);
  std::printf("%s\n", describe(got.at(0)).c_str());
}

}  // namespace
}  // namespace lancer
