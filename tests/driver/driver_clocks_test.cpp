// The clock a run quotes its rates at (driver/clocks.h): the slowest unit's
// estimate at the build's widths, a fallback without one, an option over both.

#include <gtest/gtest.h>

#include <algorithm>

#include "common/error.h"
#include "driver/clocks.h"
#include "golden/formats.h"

namespace lancer {
namespace {

UnitClock row(std::string top, int pos, int dir, int depth, double mhz) {
  UnitClock c;
  c.top = std::move(top);
  c.posBits = pos;
  c.dirBits = dir;
  c.logicDepth = depth;
  c.fmaxMhz = mhz;
  return c;
}

const std::vector<UnitClock> kTable = {
    row("rt_isect", 16, 16, 51, 749), row("rt_grid", 16, 16, 161, 245), row("rt_octree", 16, 16, 185, 213),
    row("rt_isect", 10, 10, 45, 844), row("rt_grid", 10, 10, 150, 262),
};

TEST(RunClock, TheSlowestUnitOfTheRunAtTheBuildsWidths) {
  const RunClock grid = chooseRunClock(kTable, fx::UnitKind::Grid, 16, 16, std::nullopt);
  EXPECT_EQ(grid.source, RunClock::Source::Estimate);
  EXPECT_EQ(grid.mhz, 245);
  EXPECT_EQ(grid.estimate->top, "rt_grid");
  EXPECT_NE(grid.describe().find("the estimated clock of the slowest unit, rt_grid at 16/16 (logic depth 161"),
            std::string::npos)
      << grid.describe();

  // The isect path runs the pipeline only.
  const RunClock isect = chooseRunClock(kTable, fx::UnitKind::Isect, 10, 10, std::nullopt);
  EXPECT_EQ(isect.mhz, 844);
  EXPECT_EQ(isect.estimate->where(), "rt_isect at 10/10");

  // A unit is never quoted faster than the pipeline inside it.
  std::vector<UnitClock> fastWalk = kTable;
  fastWalk[1].fmaxMhz = 900;
  EXPECT_EQ(chooseRunClock(fastWalk, fx::UnitKind::Grid, 16, 16, std::nullopt).estimate->top, "rt_isect");

  // A run that traces quadrics runs the quadric pipeline too, and waits for the slower.
  std::vector<UnitClock> withQuadric = kTable;
  withQuadric.push_back(row("rt_quadric", 16, 16, 60, 700));
  const RunClock quadrics = chooseRunClock(withQuadric, fx::UnitKind::Isect, 16, 16, std::nullopt, true);
  EXPECT_EQ(quadrics.estimate->top, "rt_quadric");
  EXPECT_EQ(quadrics.mhz, 700);
  EXPECT_EQ(chooseRunClock(withQuadric, fx::UnitKind::Isect, 16, 16, std::nullopt).estimate->top, "rt_isect")
      << "a scene of triangles only does not wait for rt_quadric";
}

TEST(RunClock, WithoutARowAtTheWidthsTheSlowestMeasuredIsUsedAndSaidSo) {
  const RunClock octree = chooseRunClock(kTable, fx::UnitKind::Octree, 10, 10, std::nullopt);
  EXPECT_EQ(octree.source, RunClock::Source::Fallback);
  EXPECT_EQ(octree.mhz, 213);
  EXPECT_NE(octree.describe().find("not every unit of this run synthesized at 10/10"), std::string::npos) << octree.describe();
  EXPECT_EQ(octree.toJson()["kind"], "fallback");
}

TEST(RunClock, AnOptionWinsAndTheSummarySaysItOverridesTheEstimate) {
  const RunClock clock = chooseRunClock(kTable, fx::UnitKind::Octree, 16, 16, 500.0);
  EXPECT_EQ(clock.source, RunClock::Source::Option);
  EXPECT_EQ(clock.mhz, 500);
  EXPECT_DOUBLE_EQ(clock.hz(), 500e6);
  EXPECT_NE(clock.describe().find("--clock-mhz, overriding the estimate of 213 MHz for rt_octree at 16/16"),
            std::string::npos)
      << clock.describe();
  const nlohmann::json j = clock.toJson();
  EXPECT_EQ(j["kind"], "option");
  EXPECT_EQ(j["estimate"]["fmax_mhz"], 213);

  EXPECT_THROW(chooseRunClock(kTable, fx::UnitKind::Grid, 16, 16, -5.0), InputError);
  EXPECT_THROW(chooseRunClock(kTable, fx::UnitKind::Grid, 16, 16, 0.0), InputError);
}

TEST(RunClock, NoEstimateAndNoOptionIsAnErrorThatSaysWhatToDo) {
  const std::vector<UnitClock> none;
  try {
    chooseRunClock(none, fx::UnitKind::Grid, 16, 16, std::nullopt);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("give --clock-mhz"), std::string::npos) << e.what();
  }
  EXPECT_EQ(chooseRunClock(none, fx::UnitKind::Grid, 16, 16, 100.0).mhz, 100);
}

TEST(UnitClocks, AMalformedTableNamesItselfAndTheRow) {
  EXPECT_THROW(parseUnitClocks("[]", "t.json"), InputError);
  EXPECT_THROW(parseUnitClocks("{not json", "t.json"), InputError);
  try {
    parseUnitClocks(R"({"units": [{"top": "rt_grid", "pos_bits": 16, "dir_bits": 16, "logic_depth": 1, "fmax_mhz": 0}]})",
                    "t.json");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("t.json: row 0"), std::string::npos) << e.what();
  }
}

// The committed table (rtl/synth/clocks.json, compiled in) has every unit at
// this build's widths, so the CI builds (16/16 and 10/10) quote estimates, and
// each row's clock is the gate model's for its depth.
TEST(UnitClocks, TheBuiltTableHasEveryUnitAtThisBuildsWidths) {
  const std::span<const UnitClock> table = unitClocks();
  for (const char* top : {"rt_isect", "rt_grid", "rt_octree"}) {
    const auto it = std::find_if(table.begin(), table.end(), [&](const UnitClock& c) {
      return c.top == top && c.posBits == fx::kPosBits && c.dirBits == fx::kDirBits;
    });
    ASSERT_NE(it, table.end()) << top << " at " << fx::kPosBits << "/" << fx::kDirBits
                               << ": run scripts/clock-table in a tree of these widths";
    EXPECT_GT(it->logicDepth, 0);
    EXPECT_NEAR(it->fmaxMhz, 1e6 / (60.0 + 25.0 * it->logicDepth), 0.1) << top;
  }
  for (const fx::UnitKind path : {fx::UnitKind::Isect, fx::UnitKind::Grid, fx::UnitKind::Octree}) {
    EXPECT_EQ(runClock(path, std::nullopt).source, RunClock::Source::Estimate);
  }
}

}  // namespace
}  // namespace lancer
