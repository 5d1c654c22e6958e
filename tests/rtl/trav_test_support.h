#pragma once

// What the tests of the Verilated traversal units (trav_rtl_suite.h and each
// unit's own tests) share besides the comparison with golden
// (support/trav_compare.h): the device a program shares, the option checks,
// the waveform, and the performance sweep.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "driver/clocks.h"
#include "driver/traversal_device.h"
#include "golden/units.h"

namespace lancer::rtltest {

using fx::kDirMax;
using fx::kPosMax;
using fx::QRay;

// The device a test program shares between its tests (made on first use).
template <class Device>
Device& sharedDevice() {
  static Device device;
  return device;
}

// raysInFlight above the unit's slots is an InputError naming both numbers
// and the CMake option for more; a negative one too, even without rays.
template <class Image>
void expectRejectsRaysInFlight(TraversalDevice<Image>& rtl, const Image& image, const std::vector<fx::QRay>& one,
                               const std::string& cmakeOption) {
  std::vector<fx::TraversalTrace> traces;
  TraversalRunOptions o;
  o.raysInFlight = rtl.maxRaysInFlight() + 1;
  try {
    rtl.run(image, one, traces, o);
    ADD_FAILURE() << "no InputError for " << o.raysInFlight << " rays in flight";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(std::to_string(o.raysInFlight)), std::string::npos) << what;
    EXPECT_NE(what.find(std::to_string(rtl.maxRaysInFlight())), std::string::npos) << what;
    EXPECT_NE(what.find(cmakeOption), std::string::npos) << what;
  }
  o.raysInFlight = -1;
  EXPECT_THROW(rtl.run(image, std::vector<fx::QRay>{}, traces, o), InputError);
  o.raysInFlight = 0;
  o.memLatency = 0;
  EXPECT_THROW(rtl.run(image, one, traces, o), InputError);
  o.memLatency = 3;
  o.memLatencyJitter = -1;
  EXPECT_THROW(rtl.run(image, one, traces, o), InputError);
}

// A temporary waveform path for `test`, removed now and by expectWaveform.
inline std::string wavePath(const std::string& test) {
  const std::string path = ::testing::TempDir() + test + ".fst";
  std::remove(path.c_str());
  return path;
}

// The FST file a run wrote is there and not empty; removes it.
inline void expectWaveform(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  ASSERT_NE(f, nullptr) << path;
  std::fseek(f, 0, SEEK_END);
  EXPECT_GT(std::ftell(f), 1000) << path;
  std::fclose(f);
  std::remove(path.c_str());
}

// The side of the sweep's camera image: `env` if set, else 256.
inline int sweepSide(const char* env) {
  const char* value = std::getenv(env);
  return value ? std::atoi(value) : 256;
}

// Performance sweep, not a check (docs/grid-unit.md, docs/octree-unit.md have
// the tables): all slots' subsets at latency 20, then all slots at latencies
// 1 .. 100; cycles, rates per cycle, and the host's rays per second. Rays/s
// at the unit's estimated clock (driver/clocks.h).
template <class Image>
void printSweep(TraversalDevice<Image>& rtl, const Image& image, const std::vector<fx::QRay>& rays) {
  const RunClock clock = runClock(fx::UnitFor<Image>::kKind, std::nullopt);
  fmt::print("clock: {}\n", clock.describe());
  fmt::print("{:>6} {:>7} {:>10} {:>9} {:>10} {:>11} {:>10} {:>13} {:>11}\n", "slots", "latency", "cycles",
             "tests/cyc", "steps/cyc", "steps/ready", "isect busy", fmt::format("Mrays/s@{:.0f}M", clock.mhz),
             "host ray/s");
  auto one = [&](int slots, int latency) {
    TraversalRunOptions o;
    o.memLatency = latency;
    o.raysInFlight = slots;
    std::vector<fx::TraversalTrace> traces;
    const auto start = std::chrono::steady_clock::now();
    const TraversalRunStats st = rtl.run(image, rays, traces, o);
    const double host = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double c = double(st.cycles);
    fmt::print("{:>6} {:>7} {:>10} {:>9.3f} {:>10.3f} {:>11.3f} {:>9.1f}% {:>13.2f} {:>11.0f}\n", slots, latency,
               st.cycles, double(st.isectTests) / c, double(st.steps) / c,
               double(st.steps) / double(std::max<uint64_t>(1, st.stepReadyCycles)),
               100.0 * double(st.isectBusyCycles) / c, double(st.rays) / c * clock.mhz, double(st.rays) / host);
  };
  const int max = rtl.maxRaysInFlight();
  for (int slots : {1, 4, 8, 16, 32}) {
    if (slots <= max) one(slots, 20);
  }
  for (int latency : {1, 10, 50, 100}) one(max, latency);
}

}  // namespace lancer::rtltest
