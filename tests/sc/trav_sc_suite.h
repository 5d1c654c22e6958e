#pragma once

// What every traversal unit's SystemC side must do, as one typed suite over
// the unit's descriptor (tests/support/unit_traits.h): each implementation
// (the cycle model, the Verilated RTL in SystemC, and what else the unit
// has) against the golden walk on the bunny's camera rays and the unit's hard
// cases, with one slot and all, with and without backpressure; repeatable
// runs; no rays and bad options; the cycle model against the Verilated RTL
// cycle for cycle and port for port; against the C++ Verilated device; the
// device names; the RTL's waveform; runs interleaved with another unit's in
// one kernel. Each unit's test program instantiates it (trav_sc_units.cpp,
// compiled once a unit by tests/sc/CMakeLists.txt); the unit's own file keeps
// only what is its own, using ScUnit.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/trav_compare.h"
#include "trav_sc_fixture.h"

namespace lancer::test {

// A unit's SystemC runs: UnitRuns, the implementations the build has, the
// cases compared cycle for cycle.
template <class Desc>
struct ScUnit : UnitRuns<Desc> {
  using Traits = UnitTraits<Desc>;
  using Image = typename Traits::Image;
  using Device = typename Traits::SystemC;
  using Case = TraversalCase<Image>;
  using UnitRuns<Desc>::rough;
  using UnitRuns<Desc>::bunnyCase;

  // The implementations of the unit this build has.
  static std::vector<SystemCImpl> impls() {
    std::vector<SystemCImpl> out;
    for (SystemCImpl impl : Traits::kScImpls) {
      if (implAvailable<Device>(impl)) out.push_back(impl);
    }
    return out;
  }

  // The bunny at 16 x 16 and the hard cases the unit compares cycle for cycle.
  static std::vector<Case> cycleCases() {
    std::vector<Case> cases{bunnyCase(16)};
    for (Case& c : Traits::hardCases()) {
      if (Traits::cycleCase(c.name)) cases.push_back(std::move(c));
    }
    return cases;
  }
  static std::vector<TraversalRunOptions> timingSettings() { return test::timingSettings(rough, 31, 33, 34); }
};

template <class Desc>
class ScTraversal : public ::testing::Test, public ScUnit<Desc> {};

TYPED_TEST_SUITE_P(ScTraversal);

TYPED_TEST_P(ScTraversal, MatchesGoldenOnBunnyCameraRays) {
  using U = ScUnit<TypeParam>;
  const auto c = U::bunnyCase(32);
  for (SystemCImpl impl : U::impls()) {
    typename U::Device device(impl);
    U::expectSameTraces(device, c.image, c.rays, U::rough(1), fmt::format("{}: {}, rough", device.name(), c.name));
  }
}

// Every hard case with all slots, then a third of its rays with one slot
// (one slot walks them one after the other).
TYPED_TEST_P(ScTraversal, MatchesGoldenOnHardCasesWithAllSlotsAndOneSlot) {
  using U = ScUnit<TypeParam>;
  const auto cases = U::Traits::hardCases();
  for (SystemCImpl impl : U::impls()) {
    typename U::Device device(impl);
    uint64_t seed = 20;
    for (const auto& c : cases) {
      SCOPED_TRACE(c.name);
      const std::string what = fmt::format("{}: {}", device.name(), c.name);
      U::expectSameTraces(device, c.image, c.rays, U::rough(++seed), what + ", all slots");
      const std::vector<fx::QRay> some(c.rays.begin(), c.rays.begin() + std::max<size_t>(1, c.rays.size() / 3));
      U::expectSameTraces(device, c.image, some, U::rough(++seed, 1), what + ", one slot");
    }
  }
}

TYPED_TEST_P(ScTraversal, MatchesGoldenWithOneSlotAllSlotsAndWithoutBackpressure) {
  using U = ScUnit<TypeParam>;
  const auto c = U::bunnyCase(10);
  for (SystemCImpl impl : U::impls()) {
    typename U::Device device(impl);
    const std::string what = fmt::format("{}: {}", device.name(), c.name);
    U::expectSameTraces(device, c.image, c.rays, U::rough(15, 1), what + ", one slot");
    U::expectSameTraces(device, c.image, c.rays, U::rough(16, device.maxRaysInFlight()), what + ", all slots");
    TraversalRunOptions fast;  // no jitter, no stalls, latency 1
    fast.memLatency = 1;
    U::expectSameTraces(device, c.image, c.rays, fast, what + ", latency 1, no backpressure");
    U::expectSameTraces(device, c.image, c.rays, {}, what + ", latency 20, no backpressure");
    TraversalRunOptions slow = U::rough(9, 3);
    slow.memLatency = 60;
    slow.memLatencyJitter = 60;
    slow.stream.outputStallProbability = 0.7;
    U::expectSameTraces(device, c.image, c.rays, slow, what + ", latency 60 + jitter 60, stalls 0.7, 3 slots");
  }
}

TYPED_TEST_P(ScTraversal, RepeatedRunsAreIndependentAndReproducible) {
  using U = ScUnit<TypeParam>;
  const auto c = U::bunnyCase(6);
  for (SystemCImpl impl : U::impls()) {
    SCOPED_TRACE(int(impl));
    expectRepeatableRuns<typename U::Device>(impl, c.image, c.rays, U::rough(3), U::rough(4));
  }
}

TYPED_TEST_P(ScTraversal, EmptyRunAndInvalidOptions) {
  using U = ScUnit<TypeParam>;
  const typename U::Image image = U::Traits::empty();
  for (SystemCImpl impl : U::impls()) {
    typename U::Device device(impl);
    expectEmptyRun<typename U::Image>(device, image);
    expectInvalidOptionsRejected<typename U::Image>(device, image);
    // Still usable afterwards.
    const std::vector<fx::QRay> one{fx::QRay{0, {0, 0, 0}, {fx::kDirMax, 0, 0}}};
    U::expectSameTraces(device, image, one, {}, fmt::format("{}: after errors", device.name()));
  }
}

// Triangles, spheres and cones in one image: every implementation with
// rt_quadric against golden (the mixed system, whose rt_isect is the Verilated
// one and which has no rt_quadric, refuses them by name), and the cycle model
// against the Verilated RTL cycle for cycle.
TYPED_TEST_P(ScTraversal, MixedPrimitivesMatchGoldenAndTheRtl) {
  using U = ScUnit<TypeParam>;
  const auto c = U::mixedCase(24, 48, 300, 4047);
  for (SystemCImpl impl : U::impls()) {
    typename U::Device device(impl);
    std::vector<fx::TraversalTrace> traces;
    if (impl == SystemCImpl::ModelRtlIsect) {
      EXPECT_THROW(device.run(c.image, c.rays, traces, U::rough(48)), InputError);
      continue;
    }
    U::expectSameTraces(device, c.image, c.rays, U::rough(48), fmt::format("{}: {}", device.name(), c.name));
  }
  expectModelMatchesRtlCycleForCycle<typename U::Device, typename U::Traits::Verilator>(std::vector{c},
                                                                                       U::timingSettings());
}

TYPED_TEST_P(ScTraversal, ModelMatchesVerilatedRtlCycleForCycle) {
  using U = ScUnit<TypeParam>;
  expectModelMatchesRtlCycleForCycle<typename U::Device, typename U::Traits::Verilator>(U::cycleCases(),
                                                                                       U::timingSettings());
}

TYPED_TEST_P(ScTraversal, StatsEqualTheCxxVerilatedDevice) {
  using U = ScUnit<TypeParam>;
  const std::vector<TraversalRunOptions> settings = U::timingSettings();
  expectStatsEqualTheCxxVerilatedDevice<TypeParam, typename U::Device>(
      U::cycleCases(), {settings[0], settings[2], settings[4]}, U::impls());
}

TYPED_TEST_P(ScTraversal, NamesAndFactory) {
  using U = ScUnit<TypeParam>;
  expectNamesAndFactory<TypeParam, typename U::Device>(U::Traits::kScRaysInFlight);
}

TYPED_TEST_P(ScTraversal, WaveformOfTheRtlOnRequest) {
  using U = ScUnit<TypeParam>;
  const auto c = U::bunnyCase(3);
  expectRtlWave<typename U::Device>(fmt::format("{}_sc_wave.fst", TypeParam::kNames.unit), U::rough(60),
                                    [&](typename U::Device& rtl, const TraversalRunOptions& o) {
                                      U::expectSameTraces(rtl, c.image, c.rays, o, "with waves");
                                    });
}

// Any SystemC system may run first; all are elaborated together in one kernel:
// the unit's runs interleaved with another unit's (the pin-level models, which
// run in the kernel, and the value-port model between them).
TYPED_TEST_P(ScTraversal, SharesTheKernelWithAnotherUnit) {
  using U = ScUnit<TypeParam>;
  using P = ScUnit<typename U::Traits::KernelPartner>;
  const QuantizedScene q = U::bunny(4, 4);
  const typename U::Image mine = U::Traits::image(q.triangles);
  const typename P::Image theirs = P::Traits::image(q.triangles);
  for (int round = 0; round < 2; ++round) {
    std::vector<fx::TraversalTrace> want, got;
    typename P::Traits::Golden().run(theirs, q.rays, want);
    typename P::Device(SystemCImpl::Pins).run(theirs, q.rays, got, U::rough(40 + round));
    EXPECT_EQ(got, want);
    for (const SystemCImpl impl : {SystemCImpl::Pins, SystemCImpl::Model}) {
      typename U::Device device(impl);
      U::expectSameTraces(device, mine, q.rays, U::rough(50 + round), "interleaved");
    }
  }
}

REGISTER_TYPED_TEST_SUITE_P(ScTraversal, MatchesGoldenOnBunnyCameraRays, MatchesGoldenOnHardCasesWithAllSlotsAndOneSlot,
                            MixedPrimitivesMatchGoldenAndTheRtl,
                            MatchesGoldenWithOneSlotAllSlotsAndWithoutBackpressure,
                            RepeatedRunsAreIndependentAndReproducible, EmptyRunAndInvalidOptions,
                            ModelMatchesVerilatedRtlCycleForCycle, StatsEqualTheCxxVerilatedDevice, NamesAndFactory,
                            WaveformOfTheRtlOnRequest, SharesTheKernelWithAnotherUnit);

}  // namespace lancer::test
