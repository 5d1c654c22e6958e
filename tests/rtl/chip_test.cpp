// A chip of N traversal units sharing one memory system (docs/chip.md): every
// ray bit-exact with the golden model for N = 1, 3 and 16 on the memory
// hierarchy, in every model (Verilated, SystemC cycle model, Verilated in
// SystemC), with the same cycles and memory figures in all of them; every unit
// takes a share of the rays; a run is the same twice and whatever the host
// threads; more units take fewer cycles; impossible chips are one-line errors
// naming their option.

#include <gtest/gtest.h>

#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "driver/job.h"
#include "support/cornell_rays.h"

namespace lancer {
namespace {

const CornellRays& cornell() {
  static const CornellRays c(48);
  return c;
}

// Small caches, so that the L1s and the L2 miss and the DRAM queues fill.
JobConfig smallHierarchy(int units) {
  JobConfig config;
  config.model = "rtl";
  config.units = units;
  config.memory.kind = mem::MemoryKind::Hierarchy;
  config.memory.l1.kib = 1;
  config.memory.l2.kib = 16;
  config.memory.dram.gbps = 6.4;
  config.memory.clockMhz = 700;
  config.raysPerBatch = 1024;
  return config;
}

size_t inLattice(const JobResult& job) {
  size_t n = 0;
  for (const auto& r : job.rays) n += r.has_value();
  return n;
}

class ChipOfUnits : public ::testing::TestWithParam<fx::UnitKind> {};

TEST_P(ChipOfUnits, EveryRayBitExactForOneThreeAndSixteenUnits) {
  const CornellRays& c = cornell();
  for (const int units : {1, 3, 16}) {
    SCOPED_TRACE(fmt::format("{} units", units));
    const JobResult job = runJob(GetParam(), c.scene, c.rays, c.quantizer, smallHierarchy(units));
    EXPECT_EQ(job.mismatchedRays, 0u);
    ASSERT_TRUE(job.chip.has_value());
    ASSERT_EQ(job.chip->units(), units);
    uint64_t taken = 0;
    for (int u = 0; u < units; ++u) {
      EXPECT_GT(job.chip->unitRays[size_t(u)], 0u) << "unit " << u << " took no ray";
      EXPECT_GT(job.chip->unitBusyCycles[size_t(u)], 0u);
      EXPECT_LE(job.chip->unitBusyCycles[size_t(u)], job.cycles);
      taken += job.chip->unitRays[size_t(u)];
    }
    EXPECT_EQ(taken, inLattice(job));
    const mem::MemoryStats& m = job.chip->stats;
    EXPECT_EQ(m.reads, job.memoryReads);
    EXPECT_GT(m.l1Total().hits, 0u);
    EXPECT_GT(m.dramBytes, 0u);
    EXPECT_EQ(m.dramLines, m.l2.misses);
  }
}

// The same chip, whichever model runs its units: the same cycles, the same
// share of rays and busy cycles per unit, the same memory figures.
TEST_P(ChipOfUnits, EveryModelGivesTheSameCycles) {
  const CornellRays& c = cornell();
  for (const int units : {1, 3, 16}) {
    SCOPED_TRACE(fmt::format("{} units", units));
    const JobResult rtl = runJob(GetParam(), c.scene, c.rays, c.quantizer, smallHierarchy(units));
    for (const char* model : {"systemc", "rtl-systemc"}) {
      SCOPED_TRACE(model);
      JobConfig config = smallHierarchy(units);
      config.model = model;
      const JobResult other = runJob(GetParam(), c.scene, c.rays, c.quantizer, config);
      EXPECT_EQ(other.mismatchedRays, 0u);
      EXPECT_EQ(other.cycles, rtl.cycles);
      EXPECT_EQ(other.memoryReads, rtl.memoryReads);
      ASSERT_TRUE(other.chip.has_value());
      EXPECT_EQ(other.chip->unitRays, rtl.chip->unitRays);
      EXPECT_EQ(other.chip->unitBusyCycles, rtl.chip->unitBusyCycles);
      EXPECT_EQ(nlohmann::json(other.chip->stats).dump(), nlohmann::json(rtl.chip->stats).dump());
    }
  }
}

TEST_P(ChipOfUnits, ARunIsTheSameTwiceAndWhateverTheHostThreads) {
  const CornellRays& c = cornell();
  JobConfig one = smallHierarchy(5);
  one.hostThreads = 1;
  JobConfig two = one;
  two.hostThreads = 2;
  const JobResult a = runJob(GetParam(), c.scene, c.rays, c.quantizer, one);
  const JobResult b = runJob(GetParam(), c.scene, c.rays, c.quantizer, one);
  const JobResult t = runJob(GetParam(), c.scene, c.rays, c.quantizer, two);
  for (const JobResult* other : {&b, &t}) {
    EXPECT_EQ(other->cycles, a.cycles);
    EXPECT_EQ(other->chip->unitRays, a.chip->unitRays);
    EXPECT_EQ(other->chip->unitBusyCycles, a.chip->unitBusyCycles);
    EXPECT_EQ(nlohmann::json(other->chip->stats).dump(), nlohmann::json(a.chip->stats).dump());
  }
}

// Simulated cycles, not host time: four units on the fixed memory finish the
// same rays in well under half the cycles of one.
TEST_P(ChipOfUnits, FourUnitsTakeFewerCyclesThanOne) {
  const CornellRays& c = cornell();
  JobConfig config;
  config.model = "rtl";
  config.raysPerBatch = 4096;
  const JobResult one = runJob(GetParam(), c.scene, c.rays, c.quantizer, config);
  config.units = 4;
  const JobResult four = runJob(GetParam(), c.scene, c.rays, c.quantizer, config);
  EXPECT_EQ(four.mismatchedRays, 0u);
  EXPECT_LT(double(four.cycles), 0.4 * double(one.cycles)) << one.cycles << " cycles on one unit";
}

TEST_P(ChipOfUnits, ImpossibleChipsNameTheirOption) {
  const CornellRays& c = cornell();
  const auto fails = [&](JobConfig config, const std::string& option) {
    try {
      runJob(GetParam(), c.scene, c.rays, c.quantizer, config);
      ADD_FAILURE() << option << ": accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(option + " ", 0), 0u) << e.what();
    }
  };
  JobConfig config = smallHierarchy(1);
  config.units = 0;
  fails(config, "--units");
  config.units = 65;
  fails(config, "--units");
  config = smallHierarchy(2);
  config.memory.l2.kib = 3;
  fails(config, "--l2-kib");
  config = smallHierarchy(2);
  config.memory.dram.gbps = 0;
  fails(config, "--dram-gbps");
  config = smallHierarchy(17);
  config.model = "systemc-pins";
  fails(config, "--units");  // the SystemC kernel's chips have 16 units (LANCER_SC_CHIP_UNITS)
}

INSTANTIATE_TEST_SUITE_P(Units, ChipOfUnits, ::testing::Values(fx::UnitKind::Grid, fx::UnitKind::Octree),
                         [](const auto& info) { return std::string(toString(info.param)); });

}  // namespace
}  // namespace lancer
