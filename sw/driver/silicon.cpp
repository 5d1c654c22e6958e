#include "driver/silicon.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

namespace lancer {

namespace detail {
// rtl/synth/sram/sram.json as the build found it (generated sram_table.cpp).
extern const char kSramJson[];
}  // namespace detail

const nlohmann::json& sramTable() {
  static const nlohmann::json table = [] {
    nlohmann::json j = nlohmann::json::parse(detail::kSramJson, nullptr, false);
    if (j.is_discarded() || !j.contains("kinds") || !j.contains("dram")) {
      throw std::runtime_error("rtl/synth/sram/sram.json (as built): not the memory table");
    }
    return j;
  }();
  return table;
}

namespace {

constexpr double kCellSupplyVolts = 1.8;  // SKY130 hd, tt_025C_1v80

// Piecewise linear in log-log through (xs, ys), the end segments extended:
// the CACTI table's own interpolation (rtl/synth/sram/cacti-table --query).
double interpolateLogLog(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  size_t i = 0;
  while (i + 2 < xs.size() && x > xs[i + 1]) ++i;
  const double f = (std::log(x) - std::log(xs[i])) / (std::log(xs[i + 1]) - std::log(xs[i]));
  return std::exp(std::log(ys[i]) + f * (std::log(ys[i + 1]) - std::log(ys[i])));
}

SramFigures cacheSram(const char* kind, const char* sizeKey, double kib) {
  if (!(kib > 0)) throw std::invalid_argument(fmt::format("{}: a size of {} KiB", kind, kib));
  std::vector<nlohmann::json> entries;
  for (const nlohmann::json& e : sramTable()["kinds"][kind]["entries"]) {
    if (!e.contains("skipped")) entries.push_back(e);
  }
  std::sort(entries.begin(), entries.end(),
            [&](const auto& a, const auto& b) { return a[sizeKey].template get<double>() < b[sizeKey].template get<double>(); });
  std::vector<double> sizes;
  for (const auto& e : entries) sizes.push_back(e[sizeKey].get<double>());
  const auto metric = [&](const char* key) {
    std::vector<double> ys;
    for (const auto& e : entries) ys.push_back(e[key].get<double>());
    return interpolateLogLog(sizes, ys, kib);
  };
  // CACTI's interpolated supply is not the cells' 1.8 V: dynamic energy scales
  // with the square of the ratio, leakage with the ratio (first order; the same
  // in scripts/lancer_silicon.py for the units' macros).
  const double ratio = kCellSupplyVolts / sramTable()["technology"]["vdd_v"].get<double>();
  return {metric("area_mm2"), metric("read_energy_pj") * ratio * ratio, metric("write_energy_pj") * ratio * ratio,
          metric("leakage_mw") * ratio};
}

}  // namespace

SramFigures l1Sram(double kib) { return cacheSram("l1", "capacity_kib", kib); }
SramFigures l2BankSram(double bankKib) { return cacheSram("l2_bank", "bank_kib", bankKib); }
RayQueueSram rayQueueSram(double kib) {
  const int banks = int(std::ceil(kib / kRayQueueBankKib));
  return {banks, l2BankSram(kib / banks)};
}

DramEnergy dramEnergy() {
  const nlohmann::json& dram = sramTable()["dram"];
  const std::string name = dram["default"].get<std::string>();
  const nlohmann::json& i = dram["interfaces"][name];
  return {name, i["pj_per_bit"].get<double>(), i.value("citation", "")};
}

std::optional<ChipSilicon> chipSilicon(const RunClock& clock, const ChipFigures& chip, uint64_t cycles,
                                       uint64_t rays) {
  // The traversal unit's row (its synthesis holds its rt_isect), and
  // rt_quadric's when the run's scene has quadrics (the unit is mapped
  // without it: Quadrics = 0; a chip for quadrics has one beside each
  // rt_isect).
  const UnitClock* unit = nullptr;
  const UnitClock* quadric = nullptr;
  for (const UnitClock& r : clock.rows) {
    if (!r.silicon || r.top == "rt_isect") continue;
    (r.top == "rt_quadric" ? quadric : unit) = &r;
  }
  if (!unit) return std::nullopt;
  const UnitSilicon& u = *unit->silicon;

  ChipSilicon s;
  s.library = u.library;
  s.nodeNm = u.nodeNm;
  s.units = chip.units();
  s.rays = rays;
  s.seconds = double(cycles) / clock.hz();
  s.workload = u.workload;
  s.dram = dramEnergy();
  s.logicPerUnit = u.logicAreaUm2 * 1e-6;
  s.macrosPerUnit = u.macroAreaMm2();

  uint64_t busy = 0;
  for (const uint64_t b : chip.unitBusyCycles) busy += b;
  s.cellsJ = u.dynamicPjPerCycle() * 1e-12 * double(busy);
  s.macrosJ = u.macroPjPerCycleBound() * 1e-12 * double(busy);
  double leakageW = s.units * (u.leakageW + u.macroLeakageW());
  if (quadric) {
    // rt_quadric's cells: its area and leakage in every unit, and its
    // measured energy of a cycle once per quadric test (its activity is that
    // of a stream of tests: scripts/silicon-activity --accel quadric).
    const UnitSilicon& q = *quadric->silicon;
    s.quadricPerUnit = q.logicAreaUm2 * 1e-6;
    s.logicPerUnit += s.quadricPerUnit;
    s.cellsJ += q.dynamicPjPerCycle() * 1e-12 * double(chip.quadricTests);
    leakageW += s.units * q.leakageW;
  }

  const mem::MemoryConfig& m = chip.memory;
  if (m.kind == mem::MemoryKind::Hierarchy) {
    const SramFigures l1 = l1Sram(m.l1.kib);
    const SramFigures bank = l2BankSram(double(m.l2.kib) / m.l2.banks);
    s.l1PerUnit = mem::kPorts * l1.areaMm2;
    s.l2 = m.l2.banks * bank.areaMm2;
    const mem::MemoryStats::Cache l1s = chip.stats.l1Total();
    s.l1J = (double(l1s.accesses) * l1.readEnergyPj + double(l1s.misses) * l1.writeEnergyPj) * 1e-12;
    s.l2J = (double(chip.stats.l2.accesses) * bank.readEnergyPj + double(chip.stats.dramLines) * bank.writeEnergyPj) *
            1e-12;
    s.dramJ = double(chip.stats.dramBytes) * 8.0 * s.dram.pjPerBit * 1e-12;
    leakageW += (s.units * mem::kPorts * l1.leakageMw + m.l2.banks * bank.leakageMw) * 1e-3;
  }
  if (chip.schedule == Schedule::Treelet) {
    const RayQueueSram q = rayQueueSram(chip.queueConfig.kib);
    const auto accesses = [](uint64_t bytes) { return std::ceil(double(bytes) / kRayQueueAccessBytes); };
    s.queues = q.banks * q.bank.areaMm2;
    s.queuesJ = (accesses(chip.queues.bytesWritten) * q.bank.writeEnergyPj +
                 accesses(chip.queues.bytesRead) * q.bank.readEnergyPj) * 1e-12;
    leakageW += q.banks * q.bank.leakageMw * 1e-3;
  }
  s.leakageJ = leakageW * s.seconds;
  return s;
}

nlohmann::json ChipSilicon::toJson() const {
  const double perRay = rays ? 1e9 / double(rays) : 0.0;
  const double watts = seconds > 0 ? 1.0 / seconds : 0.0;
  return {
      {"library", library},
      {"node_nm", nodeNm},
      {"area_mm2",
       {{"logic_per_unit", logicPerUnit},
        {"quadric_per_unit", quadricPerUnit},
        {"macros_per_unit", macrosPerUnit},
        {"l1_per_unit", l1PerUnit},
        {"memories", units * (macrosPerUnit + l1PerUnit) + l2 + queues},
        {"l2", l2},
        {"ray_queues", queues},
        {"units", units},
        {"total", areaMm2()}}},
      {"power_w",
       {{"dynamic", (cellsJ + macrosJ + l1J + l2J + queuesJ) * watts},
        {"dynamic_cells", cellsJ * watts},
        {"dynamic_macros_bound", macrosJ * watts},
        {"dynamic_caches", (l1J + l2J) * watts},
        {"dynamic_ray_queues", queuesJ * watts},
        {"leakage", leakageJ * watts},
        {"dram", dramJ * watts},
        {"total", energyJ() * watts}}},
      {"energy_nj_per_ray",
       {{"total", nanojoulesPerRay()},
        {"cells", cellsJ * perRay},
        {"macros_bound", macrosJ * perRay},
        {"l1", l1J * perRay},
        {"l2", l2J * perRay},
        {"ray_queues", queuesJ * perRay},
        {"dram", dramJ * perRay},
        {"leakage", leakageJ * perRay}}},
      {"mrays_per_s_per_mm2", mraysPerSecondPerMm2()},
      {"silicon_model",
       {{"activity_workload", workload},
        {"dram_interface", dram.interface},
        {"dram_pj_per_bit", dram.pjPerBit},
        {"dram_citation", dram.citation},
        {"memories", "CACTI 7 at 130 nm (rtl/synth/sram/README.md)"},
        {"about", "docs/silicon.md: cells from SKY130 and OpenSTA, memories from CACTI, DRAM cited; "
                  "no clock tree, wires beyond the wire-load model, pads or I/O"}}}};
}

std::string ChipSilicon::summary() const {
  const double watts = seconds > 0 ? energyJ() / seconds : 0.0;
  const double perRay = rays ? 1e9 / double(rays) : 0.0;
  std::string out = fmt::format(
      "  silicon             {} ({} nm): {:.1f} mm² = {} x ({:.2f} cells + {:.2f} macros + {:.2f} L1) + {:.2f} L2\n",
      library, nodeNm, areaMm2(), units, logicPerUnit, macrosPerUnit, l1PerUnit, l2);
  if (quadricPerUnit > 0) out += fmt::format("                      (the cells hold rt_quadric's {:.2f})\n", quadricPerUnit);
  if (queues > 0) {
    out += fmt::format("                      + {:.2f} ray queues ({:.1f} nJ/ray of their reads and writes)\n", queues,
                       queuesJ * perRay);
  }
  out += fmt::format("  energy              {:.1f} nJ/ray (cells {:.1f}, macros ≤{:.1f}, L1 {:.1f}, L2 {:.1f}, DRAM {:.2f}, "
                     "leakage {:.1f}); {:.2f} W; {:.2f} M rays/s per mm²\n",
                     nanojoulesPerRay(), cellsJ * perRay, macrosJ * perRay, l1J * perRay, l2J * perRay, dramJ * perRay,
                     leakageJ * perRay, watts, mraysPerSecondPerMm2());
  return out;
}

}  // namespace lancer
