#pragma once

// What every Verilated traversal unit must do, as one typed suite over the
// unit's descriptor (tests/support/unit_traits.h): the unit's hard cases with
// all slots under jitter, stalls and bubbles and then with one slot; a scene
// of triangles, spheres and cones likewise; the
// bunny's random rays at several builds of the image; the bunny's camera rays; one slot, all slots and no stalls, repeatable; an FST
// waveform on request; the performance sweep (disabled: figures, not a
// check). A unit's test file instantiates it in one line and keeps only its
// own cases: its timing, its bad configurations, its assertions.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "driver/devices.h"
#include "support/trav_compare.h"
#include "trav_test_support.h"

namespace lancer::rtltest {

// A unit's Verilated runs: UnitRuns on the device the test program shares.
template <class Desc>
struct RtlUnit : test::UnitRuns<Desc> {
  using Traits = test::UnitTraits<Desc>;
  using Image = typename Traits::Image;
  using Device = typename Traits::Verilator;

  static Device& rtl() { return sharedDevice<Device>(); }
  static TraversalRunStats expectSameTraces(const Image& image, const std::vector<QRay>& rays,
                                            const TraversalRunOptions& options, Device& device = rtl()) {
    return test::UnitRuns<Desc>::expectSameTraces(device, image, rays, options, "rtl");
  }
};

template <class Desc>
class RtTraversal : public ::testing::Test, public RtlUnit<Desc> {};

TYPED_TEST_SUITE_P(RtTraversal);

// Every case with all slots under jitter, stalls and bubbles; then a third of
// its rays with one slot (it walks them one after the other).
TYPED_TEST_P(RtTraversal, HardCasesMatchGolden) {
  using U = RtlUnit<TypeParam>;
  for (const auto& c : U::Traits::hardCases()) {
    SCOPED_TRACE(c.name);
    const uint64_t seed = std::hash<std::string>{}(c.name) % 1000;
    U::expectSameTraces(c.image, c.rays, U::rough(seed));
    const std::vector<QRay> some(c.rays.begin(), c.rays.begin() + std::max<size_t>(1, c.rays.size() / 3));
    U::expectSameTraces(c.image, some, U::rough(seed + 1, 1));
  }
}

// Triangles, spheres and cones in one image: rt_quadric beside rt_isect, the
// quadric records on the triangle port, under jitter, stalls and bubbles, with
// all slots and one; the tests of each kind counted as golden counts them.
TYPED_TEST_P(RtTraversal, MixedPrimitivesMatchGolden) {
  using U = RtlUnit<TypeParam>;
  const auto c = U::mixedCase(24, 48, 600, 4046);
  U::expectSameTraces(c.image, c.rays, U::rough(46));
  const std::vector<QRay> some(c.rays.begin(), c.rays.begin() + 100);
  U::expectSameTraces(c.image, some, U::rough(47, 1));
  uint64_t quadricTests = 0;
  for (const QRay& ray : c.rays) quadricTests += TypeParam::traverse(c.image, ray).quadricTests;
  EXPECT_GT(quadricTests, c.rays.size() / 2);  // the quadric pipeline was busy
}

// The bunny's random rays through the unit's image at several builds (a leaf
// size, a depth, a resolution: UnitTraits::buildVariants).
TYPED_TEST_P(RtTraversal, BunnyRandomRaysAtSeveralBuilds) {
  using U = RtlUnit<TypeParam>;
  const test::QuantizedScene q = U::bunny(1, 1);
  const std::vector<QRay> rays = test::randomLatticeRays(2, 300);
  for (const auto& v : U::Traits::buildVariants(q.triangles)) {
    SCOPED_TRACE(v.name);
    const std::vector<QRay> some(rays.begin(), rays.begin() + std::min(v.rays, rays.size()));
    U::expectSameTraces(v.image, some, U::rough(v.seed));
  }
}

TYPED_TEST_P(RtTraversal, BunnyCameraRays) {
  using U = RtlUnit<TypeParam>;
  const auto c = U::bunnyCase(40);
  U::expectSameTraces(c.image, c.rays, U::rough(1));
}

TYPED_TEST_P(RtTraversal, OneRayInFlightAllSlotsAndNoStalls) {
  using U = RtlUnit<TypeParam>;
  const auto c = U::bunnyCase(12);
  U::expectSameTraces(c.image, c.rays, U::rough(15, 1));
  U::expectSameTraces(c.image, c.rays, U::rough(16, U::rtl().maxRaysInFlight()));
  TraversalRunOptions fast;  // no jitter, no stalls, latency 1
  fast.memLatency = 1;
  const TraversalRunStats s = U::expectSameTraces(c.image, c.rays, fast);
  // Repeated runs on one device give the same cycles.
  std::vector<fx::TraversalTrace> again;
  EXPECT_EQ(U::rtl().run(c.image, c.rays, again, fast).cycles, s.cycles);
}

TYPED_TEST_P(RtTraversal, WritesAnFstWaveformWhenAsked) {
  using U = RtlUnit<TypeParam>;
  const auto c = U::bunnyCase(4);
  const std::vector<QRay> rays(c.rays.begin(), c.rays.begin() + std::min<size_t>(8, c.rays.size()));
  TraversalRunOptions o = U::rough(18);
  o.stream.wavePath = wavePath(fmt::format("{}_wave", TypeParam::kNames.module));
  U::expectSameTraces(c.image, rays, o);
  expectWaveform(o.stream.wavePath);
  // The next run writes no waveform and still matches.
  o.stream.wavePath.clear();
  U::expectSameTraces(c.image, rays, o);
}

// Bad input the unit shares with every other: a ray-slot count outside
// 1..RaysInFlight, and a corrupt image (the unit's: a read outside its
// tables), which fails the run with a message and leaves the device working;
// the factory knows the device. (A unit's own bad input is in its test file.)
TYPED_TEST_P(RtTraversal, RejectsBadInputAndRecovers) {
  using U = RtlUnit<TypeParam>;
  const auto image = U::Traits::empty();
  const std::vector<QRay> one{QRay{0, {0, 0, 0}, {kDirMax, 0, 0}}};
  expectRejectsRaysInFlight<typename U::Image>(U::rtl(), image, one, TypeParam::kNames.slotsOption);
  const auto corrupt = U::Traits::corruptImage();
  std::vector<fx::TraversalTrace> traces;
  try {
    U::rtl().run(corrupt.image, corrupt.rays, traces, TraversalRunOptions{});
    FAIL() << "no runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(corrupt.name), std::string::npos) << e.what();
  }
  U::expectSameTraces(image, one, TraversalRunOptions{});
  EXPECT_EQ(makeTraversalDevice<TypeParam>("rtl")->name(), "rtl");
  EXPECT_EQ(makeTraversalDevice<TypeParam>("rtl")->maxRaysInFlight(), U::rtl().maxRaysInFlight());
}

// Performance sweep, not a check (the unit's doc has the table). Run with
//   build/tests/rtl/rtl_<unit>_tests --gtest_also_run_disabled_tests --gtest_filter='*Sweep*'
// LANCER_SWEEP_SIZE sets the image side (default 256).
TYPED_TEST_P(RtTraversal, DISABLED_Sweep) {
  using U = RtlUnit<TypeParam>;
  const int side = sweepSide("LANCER_SWEEP_SIZE");
  const auto c = U::bunnyCase(side);
  fmt::print("bunny, {}, {} camera rays ({}x{})\n", U::Traits::describeImage(c.image), c.rays.size(), side, side);
  printSweep<typename U::Image>(U::rtl(), c.image, c.rays);
}

REGISTER_TYPED_TEST_SUITE_P(RtTraversal, HardCasesMatchGolden, MixedPrimitivesMatchGolden,
                            BunnyRandomRaysAtSeveralBuilds, BunnyCameraRays,
                            OneRayInFlightAllSlotsAndNoStalls, WritesAnFstWaveformWhenAsked,
                            RejectsBadInputAndRecovers, DISABLED_Sweep);

}  // namespace lancer::rtltest
