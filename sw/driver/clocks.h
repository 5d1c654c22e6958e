#pragma once
// The clock a run quotes its simulated rates at: the estimated clock of the
// slowest hardware unit in the run, at the build's widths, from the committed
// table rtl/synth/clocks.json (scripts/clock-table: Yosys's longest path
// between flip-flops and the gate model of docs/accuracy.md), compiled in so a
// run needs no source tree. An explicit --clock-mhz wins over the estimate.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "golden/unit.h"

namespace lancer {

// One row of the table: a unit synthesized at one pair of widths.
struct UnitClock {
  std::string top;  // the RTL module: "rt_isect", "rt_grid", "rt_octree"
  int posBits = 0;
  int dirBits = 0;
  int logicDepth = 0;  // gates on the longest flip-flop to flip-flop path
  double fmaxMhz = 0;  // the gate model's clock for that depth
  int64_t cells = 0;
  int64_t flipFlops = 0;
  nlohmann::json criticalPath;  // the instances that path runs through, with the gates in each
  std::string commit;                     // where it was measured

  std::string where() const;  // "rt_grid at 16/16"
  nlohmann::json toJson() const;
};

// The rows compiled into this build; throws std::runtime_error if the table
// the build embedded is malformed (a build defect, not an input error).
std::span<const UnitClock> unitClocks();
// Parses a table's text (the committed file's format); InputError naming `where`.
std::vector<UnitClock> parseUnitClocks(const std::string& text, const std::string& where);

// The RTL units a hardware path runs: rt_isect, and the traversal unit's top.
std::vector<std::string> rtlTops(fx::UnitKind path);

struct RunClock {
  enum class Source {
    Estimate,  // the slowest unit's row at the build's widths
    Fallback,  // a unit of the run has no row at these widths: the slowest row of the run's units at any widths
    Option,    // --clock-mhz
  };
  double mhz = 0;
  Source source = Source::Estimate;
  std::optional<UnitClock> estimate;  // the row the estimate came from (none only for an option without rows)
  int posBits = 0;                    // the build's widths
  int dirBits = 0;

  double hz() const { return mhz * 1e6; }
  std::string describe() const;  // one line for a summary
  nlohmann::json toJson() const;  // the report's clock_source
};

// The clock of a run of `path` at the given widths from `table`: the option if
// given, else the estimate. InputError if there is neither.
RunClock chooseRunClock(std::span<const UnitClock> table, fx::UnitKind path, int posBits, int dirBits,
                        std::optional<double> optionMhz);
// The same from this build's table and widths.
RunClock runClock(fx::UnitKind path, std::optional<double> optionMhz);

}  // namespace lancer
