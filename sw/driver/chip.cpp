#include "driver/chip.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "driver/traversal_device.h"

namespace lancer {

void checkChipOptions(const TraversalRunOptions& options) {
  if (options.units < 1 || options.units > kMaxUnits) {
    throw InputError(fmt::format("--units {}: a chip has 1 to {} units", options.units, kMaxUnits));
  }
  if (options.dispatchBatch < 1) {
    throw InputError(fmt::format("--dispatch-batch {}: must be at least 1", options.dispatchBatch));
  }
  if (options.hostThreads < 0) {
    throw InputError(fmt::format("--host-threads {}: must be 0 (one per core) or more", options.hostThreads));
  }
  memoryConfigOf(options).validate();
}

}  // namespace lancer

namespace lancer {

ChipFigures& ChipFigures::operator+=(const ChipFigures& o) {
  memory = o.memory;
  addPerUnit(unitRays, o.unitRays);
  addPerUnit(unitBusyCycles, o.unitBusyCycles);
  stats += o.stats;
  return *this;
}

namespace {

double ratio(double a, double b) { return b > 0 ? a / b : 0.0; }

}  // namespace

nlohmann::json ChipFigures::toJson(uint64_t cycles, uint64_t rays, double clockHz) const {
  std::vector<double> busy;
  for (uint64_t b : unitBusyCycles) busy.push_back(ratio(double(b), double(cycles)));
  const double seconds = double(cycles) / clockHz;
  nlohmann::json j = {{"units", units()},
                      {"unit_rays", unitRays},
                      {"unit_busy_fraction", busy},
                      {"rays_per_second", ratio(double(rays), seconds)},
                      {"dram_bytes", stats.dramBytes},
                      {"dram_bytes_per_ray", ratio(double(stats.dramBytes), double(rays))},
                      {"dram_gbps_used", ratio(double(stats.dramBytes), seconds) / 1e9},
                      {"memory", memory},
                      {"memory_stats", stats}};
  if (memory.kind == mem::MemoryKind::Hierarchy) {
    j["l1_hit_rate"] = stats.l1Total().hitRate();
    j["l2_hit_rate"] = stats.l2.hitRate();
  }
  j["stall_cycles"] = nlohmann::json(stats)["stall_cycles"];
  return j;
}

std::string ChipFigures::summary(uint64_t cycles, uint64_t rays, double clockHz) const {
  double busySum = 0, busyMin = 1;
  for (uint64_t b : unitBusyCycles) {
    const double f = ratio(double(b), double(cycles));
    busySum += f;
    busyMin = std::min(busyMin, f);
  }
  const double seconds = double(cycles) / clockHz;
  std::string out = fmt::format("  chip                {} unit{}, {:.1f} M rays/s; units busy {:.0f}% on average (least {:.0f}%)\n",
                                units(), units() == 1 ? "" : "s", ratio(double(rays), seconds) / 1e6,
                                100.0 * ratio(busySum, double(units())), 100.0 * busyMin);
  if (memory.kind == mem::MemoryKind::Fixed) {
    return out + fmt::format("  memory              fixed, {} cycles (+0..{} jitter)\n", memory.fixedLatency,
                             memory.fixedJitter);
  }
  const mem::MemoryStats::Cache l1 = stats.l1Total();
  out += fmt::format("  memory              L1 {} KiB x3 per unit, hit rate {:.1f}%; L2 {} KiB, hit rate {:.1f}%; "
                     "DRAM {:g} GB/s\n",
                     memory.l1.kib, 100.0 * l1.hitRate(), memory.l2.kib, 100.0 * stats.l2.hitRate(), memory.dram.gbps);
  out += fmt::format("  DRAM                {:.1f} MB, {:.0f} bytes/ray, {:.2f} GB/s used ({:.0f}% of the bandwidth)\n",
                     double(stats.dramBytes) / 1e6, ratio(double(stats.dramBytes), double(rays)),
                     ratio(double(stats.dramBytes), seconds) / 1e9,
                     100.0 * ratio(double(stats.dramBytes), seconds) / 1e9 / memory.dram.gbps);
  out += fmt::format("  stalls (cycles)     L1 full {}, L2 bank {}, L2 MSHRs {}, DRAM queue full {}, DRAM queued {}\n",
                     stats.l1FullCycles, stats.l2BankWaitCycles, stats.l2MshrFullCycles, stats.dramQueueFullCycles,
                     stats.dramQueueWaitCycles);
  return out;
}

}  // namespace lancer
