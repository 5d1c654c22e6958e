#pragma once

// A chip run's silicon (docs/silicon.md): its area, power and energy per ray at
// the library's node, from the traversal unit's standard-cell figures
// (rtl/synth/clocks.json, scripts/silicon), the CACTI table of its memories
// (rtl/synth/sram/sram.json, compiled in) and the run's own counts: busy
// cycles, L1 and L2 lookups and fills, DRAM bytes.
//
// Energy of a run, each part from what the run did:
//   cells      the unit's dynamic energy per cycle at its measured activity x busy cycles
//              (an idle unit is clock-gated: it spends leakage only); with quadrics,
//              rt_quadric's (mapped on its own) per cycle x the quadric tests
//   macros     every macro port accessed once per busy cycle (an upper bound: the RTL reads
//              its arrays combinationally, so which cycles a real macro would be read is not known)
//   L1, L2     lookups x read energy + fills x write energy (one 64-byte line each)
//   DRAM       bytes moved x 8 x the cited energy per bit of the interface
//   leakage    (cells + macros + L1s) per unit and the L2, x the run's time

#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "driver/chip.h"
#include "driver/clocks.h"

namespace lancer {

// One SRAM array of the CACTI table, at the table's node.
struct SramFigures {
  double areaMm2 = 0;
  double readEnergyPj = 0;   // one access
  double writeEnergyPj = 0;  // one access
  double leakageMw = 0;
};

// An L1 of `kib` KiB (4 ways, 64-byte lines, sequential access) and one bank of
// an L2 of `bankKib` KiB (8 ways): log-log interpolation between the table's
// CACTI points, extrapolated along the end segments.
SramFigures l1Sram(double kib);
SramFigures l2BankSram(double bankKib);
// The ray queue memory of `kib` (the treelet schedule): banks of the L2's
// kind, kRayQueueBankKib each (one bank of `kib` below that), accessed a
// 64-byte line at a time as the table's banks are.
inline constexpr double kRayQueueBankKib = 128;
inline constexpr double kRayQueueAccessBytes = 64;
struct RayQueueSram {
  int banks = 0;
  SramFigures bank;
};
RayQueueSram rayQueueSram(double kib);

// The DRAM interface the energy is priced for, with its cited figure.
struct DramEnergy {
  std::string interface;  // "LPDDR4"
  double pjPerBit = 0;
  std::string citation;
};
DramEnergy dramEnergy();

struct ChipSilicon {
  std::string library;  // "sky130_fd_sc_hd tt_025C_1v80"
  int nodeNm = 0;
  int units = 0;
  // Area, mm² (logicPerUnit holds quadricPerUnit: rt_quadric's cells, when the scene has quadrics).
  // queues: the treelet schedule's ray queue memory (none under the other schedules).
  double logicPerUnit = 0, macrosPerUnit = 0, l1PerUnit = 0, l2 = 0, quadricPerUnit = 0, queues = 0;
  // Energy of the run, joules.
  double cellsJ = 0, macrosJ = 0, l1J = 0, l2J = 0, queuesJ = 0, dramJ = 0, leakageJ = 0;
  double seconds = 0;
  uint64_t rays = 0;
  DramEnergy dram;
  std::string workload;  // where the unit's activity was measured

  double areaMm2() const { return units * (logicPerUnit + macrosPerUnit + l1PerUnit) + l2 + queues; }
  double energyJ() const { return cellsJ + macrosJ + l1J + l2J + queuesJ + dramJ + leakageJ; }
  double nanojoulesPerRay() const { return rays ? energyJ() / double(rays) * 1e9 : 0.0; }
  double mraysPerSecondPerMm2() const { return seconds > 0 ? double(rays) / seconds / 1e6 / areaMm2() : 0.0; }
  // The report's library, area_mm2, power_w, energy_nj_per_ray and mrays_per_s_per_mm2.
  nlohmann::json toJson() const;
  std::string summary() const;  // lines starting with two spaces
};

// The silicon of a chip run on `clock` (its rows name the traversal unit), or
// nothing when this build's widths have no silicon figures for that unit.
std::optional<ChipSilicon> chipSilicon(const RunClock& clock, const ChipFigures& chip, uint64_t cycles, uint64_t rays);

// The memory table as the build embedded it (rtl/synth/sram/sram.json).
const nlohmann::json& sramTable();

}  // namespace lancer
