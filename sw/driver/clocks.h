#pragma once
// The clock a run quotes its simulated rates at: the clock of the slowest
// hardware unit in the run, at the build's widths, from the committed table
// rtl/synth/clocks.json, compiled in so a run needs no source tree. A row's
// clock is OpenSTA's on SKY130 standard cells (scripts/silicon, docs/silicon.md)
// when the row has silicon figures, else the gate model's (Yosys's longest
// path between flip-flops, docs/accuracy.md); a run uses STA when every unit
// of it has it. An explicit --clock-mhz wins over both.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "golden/unit.h"

namespace lancer {

// A memory macro cut out of a unit's netlist (scripts/silicon), priced from
// the CACTI table (rtl/synth/sram/sram.json) at the library's node.
struct MacroFigures {
  std::string name;  // the RTL array: "u_slots.stack_q"
  int words = 0;
  int width = 0;
  int readPorts = 0;
  int writePorts = 0;
  double areaMm2 = 0;
  double readEnergyPj = 0;   // per read of one word
  double writeEnergyPj = 0;  // per write of one word (every replicated bank)
  double leakageMw = 0;
};

// A unit on standard cells: OpenSTA's clock, the cells' area, the macros, and
// the power OpenSTA reported at that clock (docs/silicon.md).
struct UnitSilicon {
  std::string library;      // "sky130_fd_sc_hd tt_025C_1v80"
  std::string clockSource;  // "sta sky130_fd_sc_hd tt_025C_1v80"
  int nodeNm = 0;
  double fmaxMhz = 0;
  nlohmann::json criticalPath;  // {kind, from, to}
  double logicAreaUm2 = 0;      // standard cells (fan-out buffers included)
  int64_t cells = 0;
  int64_t flipFlops = 0;
  std::vector<MacroFigures> macros;
  double powerAtMhz = 0;   // the clock the power figures were reported at
  double dynamicW = 0;     // from the measured activity of `workload` (internal + switching)
  double leakageW = 0;     // the cells' leakage
  double vectorlessW = 0;  // the vectorless figure, shown beside, never used
  std::string workload;

  double macroAreaMm2() const;
  double macroLeakageW() const;
  // The cells' dynamic energy of one cycle at the measured activity.
  double dynamicPjPerCycle() const { return powerAtMhz > 0 ? dynamicW / (powerAtMhz * 1e6) * 1e12 : 0.0; }
  // Every macro port accessed once: the macros' energy of one busy cycle, an upper bound.
  double macroPjPerCycleBound() const;
  nlohmann::json toJson() const;
};

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
  std::optional<UnitSilicon> silicon;     // on standard cells, when measured at these widths

  // The clock this row stands for: STA's when there are silicon figures, else the gate model's.
  double clockMhz(bool sta) const { return sta && silicon ? silicon->fmaxMhz : fmaxMhz; }

  std::string where() const;  // "rt_grid at 16/16"
  nlohmann::json toJson() const;
};

// The rows compiled into this build; throws std::runtime_error if the table
// the build embedded is malformed (a build defect, not an input error).
std::span<const UnitClock> unitClocks();
// Parses a table's text (the committed file's format); InputError naming `where`.
std::vector<UnitClock> parseUnitClocks(const std::string& text, const std::string& where);

// The RTL units a hardware path runs: rt_isect, the traversal unit's top, and
// rt_quadric when the run traces quadrics.
std::vector<std::string> rtlTops(fx::UnitKind path, bool quadrics = false);

struct RunClock {
  enum class Source {
    Estimate,  // the slowest unit's row at the build's widths
    Fallback,  // a unit of the run has no row at these widths: the slowest row of the run's units at any widths
    Option,    // --clock-mhz
  };
  double mhz = 0;
  Source source = Source::Estimate;
  std::optional<UnitClock> estimate;  // the row the estimate came from (none only for an option without rows)
  std::vector<UnitClock> rows;        // every unit of the run at the build's widths (those the table has)
  bool sta = false;                   // the rows' clocks are OpenSTA's (every unit of the run has silicon figures)
  int posBits = 0;                    // the build's widths
  int dirBits = 0;

  // What the estimate's clock comes from: "sta sky130_fd_sc_hd tt_025C_1v80" or "gate model".
  std::string model() const;

  double hz() const { return mhz * 1e6; }
  std::string describe() const;  // one line for a summary
  nlohmann::json toJson() const;  // the report's clock_source
};

// The clock of a run of `path` at the given widths from `table`: the option if
// given, else the estimate. InputError if there is neither.
RunClock chooseRunClock(std::span<const UnitClock> table, fx::UnitKind path, int posBits, int dirBits,
                        std::optional<double> optionMhz, bool quadrics = false);
// The same from this build's table and widths.
RunClock runClock(fx::UnitKind path, std::optional<double> optionMhz, bool quadrics = false);

}  // namespace lancer
