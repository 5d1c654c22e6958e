#pragma once

// What the SystemC tests of every traversal unit share (grid_sc_test.cpp,
// octree_sc_test.cpp, bvh_sc_test.cpp): printing a port cycle, the counters
// two runs must agree on, a run against the golden model, the cycle model
// against the Verilated RTL port trace for port trace and against the C++
// Verilated device counter for counter, the option checks, the device names,
// repeatability and the waveform of the Verilated RTL. Each unit adds its own
// expectations (the grid's cell prefetch, each unit's one-ray timing) around
// these.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "common/error.h"
#include "common/rt_trav_cycle.h"
#include "driver/devices.h"
#include "driver/traversal_device.h"

namespace lancer {
namespace sc {
inline void PrintTo(const TraversalCycle& c, std::ostream* os) {
  *os << fmt::format(
      "cycle {}: ray {}{} res {}{} visit {}{} node {}@{:#x}/{} idx {}@{:#x}/{} tri {}@{:#x}/{} fire {} step {} "
      "res [{:x}] visit [{:x}]",
      c.cycle, int(c.rayValid), int(c.rayReady), int(c.resValid), int(c.resReady), int(c.visitValid),
      int(c.visitReady), int(c.nodeReq), c.nodeAddr, c.nodeTag, int(c.idxReq), c.idxAddr, c.idxTag, int(c.triReq),
      c.triAddr, c.triTag, int(c.perfIsectFire), int(c.perfStepReady), fmt::join(c.resData, "_"),
      fmt::join(c.visitData, "_"));
}
}  // namespace sc

namespace test {

// The implementations of a SystemC traversal device (Device::Impl) as test
// parameters: tests of one the build lacks are skipped.
template <class Device>
bool implAvailable(typename Device::Impl impl) {
  using Impl = typename Device::Impl;
  if (impl == Impl::Rtl) return Device::rtlAvailable();
  if (impl == Impl::ModelRtlIsect) return Device::rtlIsectAvailable();
  return true;
}

template <class Device>
class ScTraversalTest : public ::testing::TestWithParam<typename Device::Impl> {
 protected:
  void SetUp() override {
    if (!implAvailable<Device>(this->GetParam())) GTEST_SKIP() << "this build has no Verilated RTL for this variant";
  }
};

template <class Impl>
std::string implName(const ::testing::TestParamInfo<Impl>& info) {
  switch (info.param) {
    case Impl::Model: return "Model";
    case Impl::Pins: return "Pins";
    case Impl::Rtl: return "Rtl";
    case Impl::ModelRtlIsect: return "ModelRtlIsect";
  }
  return "?";
}

// The timing settings of the port-trace comparisons: plain (latency 20,
// latency 1), `rough` with all slots (seed a) and with 3 (seed b), and slow
// with heavy stalls (seed c: latency 40 + jitter 40, stalls 0.6; the FIFOs
// fill, the arbiters skip full queues). One slot is left to the golden tests:
// it makes runs long and arbitration trivial.
inline std::vector<TraversalRunOptions> timingSettings(TraversalRunOptions (*rough)(uint64_t, int), uint64_t a,
                                                       uint64_t b, uint64_t c) {
  std::vector<TraversalRunOptions> all;
  TraversalRunOptions o;
  all.push_back(o);
  o.memLatency = 1;
  all.push_back(o);
  all.push_back(rough(a, 0));
  all.push_back(rough(b, 3));
  o = rough(c, 0);
  o.memLatency = 40;
  o.memLatencyJitter = 40;
  o.stream.outputStallProbability = 0.6;
  all.push_back(o);
  return all;
}

inline std::string optionsText(const TraversalRunOptions& o) {
  return fmt::format("latency {} jitter {} slots {} stall {} idle {} seed {}", o.memLatency, o.memLatencyJitter,
                     o.raysInFlight, o.stream.outputStallProbability, o.stream.inputIdleProbability, o.stream.seed);
}

// Every counter of two runs of the same stimulus, cycles included.
inline void expectSameStats(const TraversalRunStats& a, const TraversalRunStats& b, const std::string& what) {
  EXPECT_EQ(a.cycles, b.cycles) << what;
  EXPECT_EQ(a.rays, b.rays) << what;
  EXPECT_EQ(a.steps, b.steps) << what;
  EXPECT_EQ(a.stepReadyCycles, b.stepReadyCycles) << what;
  EXPECT_EQ(a.nodeReads, b.nodeReads) << what;
  EXPECT_EQ(a.indexReads, b.indexReads) << what;
  EXPECT_EQ(a.triangleReads, b.triangleReads) << what;
  EXPECT_EQ(a.isectTests, b.isectTests) << what;
  EXPECT_EQ(a.isectBusyCycles, b.isectBusyCycles) << what;
}

// Two devices that record port traces (SystemCTraversalDevice,
// VerilatorTraversalDevice) on the same run: the same counters and traces,
// and the same port activity in every cycle (the first three differing cycles
// reported).
template <class ModelDevice, class RtlDevice, class Image>
void expectSamePortTraces(ModelDevice& model, RtlDevice& rtl, const Image& image, const std::vector<fx::QRay>& rays,
                          const TraversalRunOptions& o, const std::string& what) {
  std::vector<sc::TraversalCycle> mt, rt;
  std::vector<fx::TraversalTrace> a, b;
  model.setCycleTrace(&mt);
  rtl.setCycleTrace(&rt);
  const TraversalRunStats sm = model.run(image, rays, a, o);
  const TraversalRunStats sr = rtl.run(image, rays, b, o);
  model.setCycleTrace(nullptr);
  rtl.setCycleTrace(nullptr);
  expectSameStats(sm, sr, what);
  EXPECT_EQ(a, b) << what;
  EXPECT_EQ(mt.size(), rt.size()) << what;
  size_t differing = 0;
  for (size_t i = 0; i < std::min(mt.size(), rt.size()); ++i) {
    if (mt[i] == rt[i]) continue;
    if (++differing <= 3) {
      ADD_FAILURE() << what << ", differing cycle\n  model: " << ::testing::PrintToString(mt[i])
                    << "\n  rtl:   " << ::testing::PrintToString(rt[i]);
    }
  }
  EXPECT_EQ(differing, 0u) << what << ": cycles whose port activity differs";
}

// Every case under every timing setting, port for port (expectSamePortTraces):
// the cycle model on value ports against the C++ Verilated RTL (`Cxx`, both
// clocked by one run loop), and, in the SystemC kernel, the cycle model on
// signals and the value-port model against the Verilated RTL there (so the
// kernel's testbench and the C++ loop drive alike). The kernel's part is
// skipped without the unit Verilated for SystemC.
template <class Device, class Cxx, class Case>
void expectModelMatchesRtlCycleForCycle(const std::vector<Case>& cases,
                                        const std::vector<TraversalRunOptions>& settings) {
  Device model(Device::Impl::Model);
  Cxx cxx;
  for (const Case& c : cases) {
    for (const TraversalRunOptions& o : settings) {
      expectSamePortTraces(model, cxx, c.image, c.rays, o, c.name + ", " + optionsText(o) + ", systemc vs rtl");
    }
  }
  if (!Device::rtlAvailable()) GTEST_SKIP() << "no Verilated unit for SystemC in this build";
  Device pins(Device::Impl::Pins), rtl(Device::Impl::Rtl);
  for (const Case& c : cases) {
    for (const TraversalRunOptions& o : settings) {
      const std::string what = c.name + ", " + optionsText(o);
      expectSamePortTraces(pins, rtl, c.image, c.rays, o, what + ", systemc-pins vs rtl-systemc");
      expectSamePortTraces(model, rtl, c.image, c.rays, o, what + ", systemc vs rtl-systemc");
    }
  }
}

// The SystemC devices of `impls` (those this build has) against the unit's C++
// Verilated device ("rtl") on the same stimulus and memory timing: the same
// counters, cycles included, and the same traces. Skipped without "rtl".
template <class Unit, class Device, class Case>
void expectStatsEqualTheCxxVerilatedDevice(const std::vector<Case>& cases,
                                           const std::vector<TraversalRunOptions>& settings,
                                           const std::vector<typename Device::Impl>& impls) {
  const std::vector<std::string> names = traversalDeviceNames<Unit>();
  if (std::find(names.begin(), names.end(), "rtl") == names.end()) {
    GTEST_SKIP() << "no C++ Verilated device (\"rtl\") in this build";
  }
  const auto cxx = makeTraversalDevice<Unit>("rtl");
  for (const Case& c : cases) {
    for (const TraversalRunOptions& o : settings) {
      std::vector<fx::TraversalTrace> want, got;
      const TraversalRunStats ref = cxx->run(c.image, c.rays, want, o);
      for (const auto impl : impls) {
        if (!implAvailable<Device>(impl)) continue;
        Device device(impl);
        const TraversalRunStats s = device.run(c.image, c.rays, got, o);
        const std::string what = fmt::format("{} vs rtl, {}, {}", device.name(), c.name, optionsText(o));
        expectSameStats(s, ref, what);
        EXPECT_EQ(got, want) << what;
      }
    }
  }
}

// The unit's device names: "systemc" always, "rtl-systemc" exactly when the
// build has the Verilated unit; each name makes the device of that name, the
// SystemC one with the unit's `raysInFlight` slots; an unknown name is an
// InputError.
template <class Unit, class Device>
void expectNamesAndFactory(int raysInFlight) {
  const std::vector<std::string> names = traversalDeviceNames<Unit>();
  EXPECT_NE(std::find(names.begin(), names.end(), "systemc"), names.end());
  EXPECT_EQ(std::find(names.begin(), names.end(), "rtl-systemc") != names.end(), Device::rtlAvailable());
  for (const std::string& n : names) EXPECT_EQ(makeTraversalDevice<Unit>(n)->name(), n);
  EXPECT_EQ(makeTraversalDevice<Unit>("systemc")->maxRaysInFlight(), raysInFlight);
  EXPECT_THROW(makeTraversalDevice<Unit>("nope"), InputError);
}

// Every option outside its range is an InputError, the slot count's naming
// both the request and the unit's slots; the device stays usable (the caller
// runs it again).
template <class Image>
void expectInvalidOptionsRejected(TraversalDevice<Image>& device, const Image& image) {
  std::vector<fx::TraversalTrace> traces;
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
  o.memLatencyJitter = -1;
  EXPECT_THROW(device.run(image, one, traces, o), InputError);
  o = {};
  o.stream.outputStallProbability = 1.0;
  EXPECT_THROW(device.run(image, one, traces, o), InputError);
  o = {};
  o.stream.inputIdleProbability = -0.1;
  EXPECT_THROW(device.run(image, one, traces, o), InputError);
}

// No rays: no traces, no cycles.
template <class Image>
void expectEmptyRun(TraversalDevice<Image>& device, const Image& image) {
  std::vector<fx::TraversalTrace> traces(3);
  const TraversalRunStats s = device.run(image, std::vector<fx::QRay>{}, traces);
  EXPECT_TRUE(traces.empty());
  EXPECT_EQ(s.cycles, 0u);
}

// Two runs of one device and one of a new device: the same seed gives the same
// counters, another seed another timing (the cycles, or the cycles some slot
// could step in, or the reads issued ahead: two seeds may happen to end in the
// same cycle), every run the same traces.
template <class Device, class Image>
void expectRepeatableRuns(typename Device::Impl impl, const Image& image, const std::vector<fx::QRay>& rays,
                          const TraversalRunOptions& seedA, const TraversalRunOptions& seedB) {
  std::vector<fx::TraversalTrace> a, b, c;
  Device first(impl);
  const TraversalRunStats sa = first.run(image, rays, a, seedA);
  const TraversalRunStats other = first.run(image, rays, b, seedB);
  Device second(impl);
  const TraversalRunStats sc = second.run(image, rays, c, seedA);
  EXPECT_EQ(a, c);
  EXPECT_EQ(a, b);  // traces do not depend on the timing
  expectSameStats(sa, sc, "same seed, new device");
  EXPECT_NE(std::tie(sa.cycles, sa.stepReadyCycles, sa.nodeReads),
            std::tie(other.cycles, other.stepReadyCycles, other.nodeReads));
}

// The FST the Verilated RTL (Device::Impl::Rtl) writes for
// StreamOptions::wavePath = TempDir()/file: `run` runs the device with the
// options; the file is there afterwards and not trivially small. Skipped
// without a Verilated unit with FST tracing.
template <class Device>
void expectRtlWave(const std::string& file, TraversalRunOptions o,
                   const std::function<void(Device&, const TraversalRunOptions&)>& run) {
  if (!Device::rtlAvailable() || !Device::wavesAvailable()) {
    GTEST_SKIP() << "no Verilated unit with FST tracing in this build";
  }
  o.stream.wavePath = ::testing::TempDir() + file;
  std::remove(o.stream.wavePath.c_str());
  Device rtl(Device::Impl::Rtl);
  run(rtl, o);
  std::FILE* f = std::fopen(o.stream.wavePath.c_str(), "rb");
  ASSERT_NE(f, nullptr) << o.stream.wavePath;
  std::fseek(f, 0, SEEK_END);
  EXPECT_GT(std::ftell(f), 1000);
  std::fclose(f);
  std::remove(o.stream.wavePath.c_str());
}

}  // namespace test
}  // namespace lancer
