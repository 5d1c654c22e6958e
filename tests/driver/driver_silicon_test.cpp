// A chip run's silicon (driver/silicon.h): the run clock from STA when every
// unit has standard-cell figures, the memories from the CACTI table, and the
// area and energy of a run from its counts.

#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "driver/clocks.h"
#include "driver/silicon.h"

namespace lancer {
namespace {

UnitSilicon silicon(double mhz, double areaUm2) {
  UnitSilicon s;
  s.library = "sky130_fd_sc_hd tt_025C_1v80";
  s.clockSource = "sta sky130_fd_sc_hd tt_025C_1v80";
  s.nodeNm = 130;
  s.fmaxMhz = mhz;
  s.logicAreaUm2 = areaUm2;
  s.powerAtMhz = mhz;
  s.dynamicW = 0.5;  // 0.5 W at `mhz`
  s.leakageW = 1e-3;
  s.macros.push_back({"u_slots.stack_q", 1024, 88, 1, 1, 0.5, 40.0, 100.0, 2.0});
  return s;
}

UnitClock row(std::string top, double gateMhz, std::optional<UnitSilicon> si) {
  UnitClock c;
  c.top = std::move(top);
  c.posBits = 16;
  c.dirBits = 16;
  c.logicDepth = 50;
  c.fmaxMhz = gateMhz;
  c.silicon = std::move(si);
  return c;
}

TEST(RunClockSta, EveryUnitWithSiliconFiguresRunsAtTheSlowestStaClock) {
  const std::vector<UnitClock> table = {row("rt_isect", 749, silicon(108, 7e5)),
                                        row("rt_bvh", 722, silicon(101, 5e6))};
  const RunClock clock = chooseRunClock(table, fx::UnitKind::Bvh, 16, 16, std::nullopt);
  EXPECT_TRUE(clock.sta);
  EXPECT_EQ(clock.mhz, 101);
  EXPECT_EQ(clock.estimate->top, "rt_bvh");
  EXPECT_EQ(clock.model(), "sta sky130_fd_sc_hd tt_025C_1v80");
  EXPECT_EQ(clock.toJson()["model"], "sta sky130_fd_sc_hd tt_025C_1v80");
  EXPECT_NE(clock.describe().find("the STA clock of the slowest unit, rt_bvh at 16/16"), std::string::npos)
      << clock.describe();
  EXPECT_EQ(clock.rows.size(), 2u);
}

TEST(RunClockSta, OneUnitWithoutSiliconFiguresKeepsTheWholeRunOnTheGateModel) {
  const std::vector<UnitClock> table = {row("rt_isect", 749, silicon(108, 7e5)), row("rt_bvh", 722, std::nullopt)};
  const RunClock clock = chooseRunClock(table, fx::UnitKind::Bvh, 16, 16, std::nullopt);
  EXPECT_FALSE(clock.sta);
  EXPECT_EQ(clock.mhz, 722);
  EXPECT_EQ(clock.model(), "gate model");
}

TEST(UnitClocksSta, AMalformedSiliconObjectNamesTheRow) {
  const char* text = R"({"units": [{"top": "rt_grid", "pos_bits": 16, "dir_bits": 16, "logic_depth": 1,
      "fmax_mhz": 300, "silicon": {"library": "x", "clock_source": "sta x", "node_nm": 130, "fmax_mhz": 0,
      "logic_area_um2": 10}}]})";
  try {
    parseUnitClocks(text, "t.json");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("t.json: row 0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("silicon.fmax_mhz"), std::string::npos) << e.what();
  }
}

TEST(SramTable, TheCachesInterpolateTheCactiPointsAtTheCellsSupply) {
  // At a grid point the figure is the table's, scaled to 1.8 V (energy by V², leakage by V).
  const nlohmann::json& table = sramTable();
  const double ratio = 1.8 / table["technology"]["vdd_v"].get<double>();
  for (const nlohmann::json& e : table["kinds"]["l1"]["entries"]) {
    if (e.contains("skipped")) continue;
    const SramFigures s = l1Sram(e["capacity_kib"].get<double>());
    EXPECT_NEAR(s.areaMm2, e["area_mm2"].get<double>(), 1e-9);
    EXPECT_NEAR(s.readEnergyPj, e["read_energy_pj"].get<double>() * ratio * ratio, 1e-6);
    EXPECT_NEAR(s.leakageMw, e["leakage_mw"].get<double>() * ratio, 1e-9);
  }
  // Between points: between their figures.
  const SramFigures a = l1Sram(16), b = l1Sram(32), mid = l1Sram(24);
  EXPECT_GT(mid.areaMm2, a.areaMm2);
  EXPECT_LT(mid.areaMm2, b.areaMm2);
  EXPECT_GT(l2BankSram(128).areaMm2, l1Sram(64).areaMm2);
  EXPECT_GT(dramEnergy().pjPerBit, 0);
  EXPECT_FALSE(dramEnergy().citation.empty());
}

TEST(ChipSiliconTest, AreaAndEnergyOfARunFromItsCounts) {
  const std::vector<UnitClock> table = {row("rt_isect", 749, silicon(120, 7e5)),
                                        row("rt_grid", 700, silicon(100, 4e6))};
  const RunClock clock = chooseRunClock(table, fx::UnitKind::Grid, 16, 16, std::nullopt);
  ASSERT_EQ(clock.mhz, 100);

  ChipFigures chip;
  chip.memory.kind = mem::MemoryKind::Hierarchy;
  chip.unitRays = {500, 500};
  chip.unitBusyCycles = {1000, 600};
  chip.stats.l1.resize(2);
  chip.stats.l1[0][0].accesses = 300;
  chip.stats.l1[0][0].misses = 10;
  chip.stats.l1[1][2].accesses = 100;
  chip.stats.l1[1][2].misses = 5;
  chip.stats.l2.accesses = 15;
  chip.stats.dramLines = 4;
  chip.stats.dramBytes = 256;
  const uint64_t cycles = 1000, rays = 1000;

  const auto s = chipSilicon(clock, chip, cycles, rays);
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->units, 2);
  const SramFigures l1 = l1Sram(chip.memory.l1.kib);
  const SramFigures bank = l2BankSram(double(chip.memory.l2.kib) / chip.memory.l2.banks);
  // Area: per unit its cells, its macro and three L1s; the L2's banks once.
  EXPECT_NEAR(s->areaMm2(), 2 * (4.0 + 0.5 + 3 * l1.areaMm2) + chip.memory.l2.banks * bank.areaMm2, 1e-9);
  // The cells: 0.5 W at 100 MHz is 5 nJ a cycle, over 1600 busy cycles.
  EXPECT_NEAR(s->cellsJ, 5e-9 * 1600, 1e-15);
  EXPECT_NEAR(s->macrosJ, (40.0 + 100.0) * 1e-12 * 1600, 1e-15);
  EXPECT_NEAR(s->l1J, (400 * l1.readEnergyPj + 15 * l1.writeEnergyPj) * 1e-12, 1e-18);
  EXPECT_NEAR(s->l2J, (15 * bank.readEnergyPj + 4 * bank.writeEnergyPj) * 1e-12, 1e-18);
  EXPECT_NEAR(s->dramJ, 256 * 8 * dramEnergy().pjPerBit * 1e-12, 1e-18);
  const double seconds = 1000 / 100e6;
  const double leakW = 2 * (1e-3 + 2e-3) + (2 * 3 * l1.leakageMw + chip.memory.l2.banks * bank.leakageMw) * 1e-3;
  EXPECT_NEAR(s->leakageJ, leakW * seconds, 1e-15);
  EXPECT_NEAR(s->nanojoulesPerRay(), s->energyJ() / 1000 * 1e9, 1e-9);
  EXPECT_NEAR(s->mraysPerSecondPerMm2(), 1000 / seconds / 1e6 / s->areaMm2(), 1e-9);

  const nlohmann::json j = s->toJson();
  EXPECT_EQ(j["library"], "sky130_fd_sc_hd tt_025C_1v80");
  EXPECT_NEAR(j["area_mm2"]["total"].get<double>(), s->areaMm2(), 1e-12);
  EXPECT_NEAR(j["energy_nj_per_ray"]["total"].get<double>(), s->nanojoulesPerRay(), 1e-12);
  EXPECT_NEAR(j["power_w"]["total"].get<double>(), s->energyJ() / seconds, 1e-9);
  EXPECT_TRUE(j["mrays_per_s_per_mm2"].is_number());
  EXPECT_NE(s->summary().find("nJ/ray"), std::string::npos);
}

// A scene with quadrics: each unit holds an rt_quadric beside its rt_isect
// (mapped on its own, its row in the run's clock), its cells' area and
// leakage in every unit, its energy of a cycle once per quadric test.
TEST(ChipSiliconTest, QuadricsAddTheQuadricPipelinePerUnit) {
  UnitSilicon quadricCells = silicon(110, 2.5e6);
  quadricCells.macros.clear();
  quadricCells.dynamicW = 0.22;  // 2 nJ a cycle at 110 MHz
  const std::vector<UnitClock> table = {row("rt_isect", 749, silicon(120, 7e5)), row("rt_quadric", 600, quadricCells),
                                        row("rt_grid", 700, silicon(100, 4e6))};
  const RunClock clock = chooseRunClock(table, fx::UnitKind::Grid, 16, 16, std::nullopt, true);
  ASSERT_EQ(clock.mhz, 100);  // the slowest of the run's units: the grid
  ChipFigures chip;
  chip.unitRays = {500, 500};
  chip.unitBusyCycles = {1000, 600};
  chip.quadricTests = 300;
  const auto s = chipSilicon(clock, chip, 1000, 1000);
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->quadricPerUnit, 2.5, 1e-12);
  EXPECT_NEAR(s->logicPerUnit, 4.0 + 2.5, 1e-12);
  EXPECT_NEAR(s->cellsJ, 5e-9 * 1600 + 2e-9 * 300, 1e-15);
  const double leakW = 2 * (1e-3 + 2e-3 + 1e-3);  // the grid's cells and macro, rt_quadric's cells
  EXPECT_NEAR(s->leakageJ, leakW * 1000 / 100e6, 1e-15);
  EXPECT_NEAR(s->toJson()["area_mm2"]["quadric_per_unit"].get<double>(), 2.5, 1e-12);
  EXPECT_NE(s->summary().find("rt_quadric"), std::string::npos);
  // Without quadrics in the scene the run's clock has no rt_quadric row: none of it.
  const RunClock plain = chooseRunClock(table, fx::UnitKind::Grid, 16, 16, std::nullopt, false);
  EXPECT_NEAR(chipSilicon(plain, chip, 1000, 1000)->logicPerUnit, 4.0, 1e-12);
}

TEST(ChipSiliconTest, NoSiliconFiguresNoFigures) {
  const std::vector<UnitClock> table = {row("rt_isect", 749, std::nullopt), row("rt_grid", 700, std::nullopt)};
  const RunClock clock = chooseRunClock(table, fx::UnitKind::Grid, 16, 16, std::nullopt);
  ChipFigures chip;
  chip.unitRays = {1};
  chip.unitBusyCycles = {1};
  EXPECT_FALSE(chipSilicon(clock, chip, 10, 1).has_value());
}

}  // namespace
}  // namespace lancer
