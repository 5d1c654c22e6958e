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
  if (options.treelets) options.queues.validate();
}

ChipFigures& ChipFigures::operator+=(const ChipFigures& o) {
  memory = o.memory;
  addPerUnit(unitRays, o.unitRays);
  addPerUnit(unitBusyCycles, o.unitBusyCycles);
  stats += o.stats;
  schedule = o.schedule;
  sort += o.sort;
  treelets += o.treelets;
  quadricTests += o.quadricTests;
  queueConfig = o.queueConfig;
  queues += o.queues;
  return *this;
}

namespace {

double ratio(double a, double b) { return b > 0 ? a / b : 0.0; }

// The figures the report and the summary both give, from the counts.
struct Rates {
  Rates(const ChipFigures& f, uint64_t cycles, uint64_t rays, double clockHz)
      : seconds(double(cycles) / clockHz),
        raysPerSecond(ratio(double(rays), seconds)),
        dramBytesPerRay(ratio(double(f.stats.dramBytes), double(rays))),
        dramGbps(ratio(double(f.stats.dramBytes), seconds) / 1e9),
        footprintBytesPerRay(ratio(double(f.stats.footprintBytes), double(rays))),
        raysPerSecondWithSort(ratio(double(rays), double(cycles + f.sort.chipCycles) / clockHz)) {
    for (uint64_t b : f.unitBusyCycles) busy.push_back(ratio(double(b), double(cycles)));
  }
  double seconds, raysPerSecond, dramBytesPerRay, dramGbps, footprintBytesPerRay;
  double raysPerSecondWithSort;  // with a chip's estimated sort added to the cycles (schedule sorted)
  std::vector<double> busy;  // per unit, the share of the cycles it had a ray in flight
};

}  // namespace

nlohmann::json ChipFigures::toJson(uint64_t cycles, uint64_t rays, double clockHz) const {
  const Rates r(*this, cycles, rays, clockHz);
  nlohmann::json j = {{"units", units()},
                      {"unit_rays", unitRays},
                      {"unit_busy_fraction", r.busy},
                      {"rays_per_second", r.raysPerSecond},
                      {"dram_bytes", stats.dramBytes},
                      {"dram_bytes_per_ray", r.dramBytesPerRay},
                      {"footprint_bytes_per_ray", r.footprintBytesPerRay},
                      {"dram_gbps_used", r.dramGbps},
                      {"memory", memory},
                      {"memory_stats", stats},
                      {"schedule", toString(schedule)}};
  if (treelets.rays > 0) {
    // Each suspension writes the walk's state to a queue and reads it back.
    const double bytes = double(treelets.stateBits) / 8.0;
    j["treelet_walk"] = {{"crossings_per_ray", ratio(double(treelets.crossings), double(treelets.rays))},
                         {"suspensions_per_ray", ratio(double(treelets.suspensions), double(treelets.rays))},
                         {"state_bytes_per_suspension", ratio(bytes, double(treelets.suspensions))},
                         {"state_bytes_per_ray", ratio(bytes, double(treelets.rays))}};
  }
  if (schedule == Schedule::Treelet) {
    j["ray_queues"] = {{"config", queueConfig},
                       {"stats", queues},
                       {"suspensions_per_ray", ratio(double(queues.suspensions), double(rays))},
                       {"queue_bytes_per_ray", ratio(double(queues.bytesWritten + queues.bytesRead), double(rays))},
                       {"overflow_dram_bytes_per_ray", ratio(double(queues.overflowBytes), double(rays))}};
  }
  if (sortsRays(schedule)) {
    // The rate with the chip's estimated sort added to the cycles, beside the rate without it.
    j["sort"] = sort;
    j["rays_per_second_with_sort"] = r.raysPerSecondWithSort;
    j["dram_bytes_per_ray_with_sort"] = ratio(double(stats.dramBytes + sort.dramBytes), double(rays));
  }
  if (memory.kind == mem::MemoryKind::Hierarchy) {
    j["l1_hit_rate"] = stats.l1Total().hitRate();
    j["l2_hit_rate"] = stats.l2.hitRate();
  }
  j["stall_cycles"] = nlohmann::json(stats)["stall_cycles"];
  return j;
}

std::string ChipFigures::summary(uint64_t cycles, uint64_t rays, double clockHz) const {
  const Rates r(*this, cycles, rays, clockHz);
  double busySum = 0, busyMin = 1;
  for (const double f : r.busy) {
    busySum += f;
    busyMin = std::min(busyMin, f);
  }
  std::string out = fmt::format("  chip                {} unit{}, {:.1f} M rays/s; units busy {:.0f}% on average (least {:.0f}%)\n",
                                units(), units() == 1 ? "" : "s", r.raysPerSecond / 1e6,
                                100.0 * ratio(busySum, double(units())), 100.0 * busyMin);
  if (schedule == Schedule::Sorted) {
    out += fmt::format("  schedule            sorted: {} rays in {} sorts; host sort {:.3f} s; a chip's sort "
                       "~{} cycles, {:.1f} MB of DRAM (estimate; {:.1f} M rays/s with it)\n",
                       sort.rays, sort.sorts, sort.hostSeconds, sort.chipCycles, double(sort.dramBytes) / 1e6,
                       r.raysPerSecondWithSort / 1e6);
  } else if (schedule == Schedule::Treelet) {
    out += fmt::format("  schedule            treelet: {:.2f} suspensions/ray, {} block switches; ray queues {} KiB "
                       "(peak {:.0f} KiB, mean {:.0f} KiB), {:.0f} queue bytes/ray; overflow {} walks, {:.1f} DRAM "
                       "bytes/ray; fresh rays launched sorted (a chip's sort ~{} cycles: {:.1f} M rays/s with it)\n",
                       ratio(double(queues.suspensions), double(rays)), queues.blockSwitches, queueConfig.kib,
                       double(queues.peakBytes) / 1024.0, ratio(double(queues.byteCycles), double(queues.cycles)) / 1024.0,
                       ratio(double(queues.bytesWritten + queues.bytesRead), double(rays)), queues.overflows,
                       ratio(double(queues.overflowBytes), double(rays)), sort.chipCycles, r.raysPerSecondWithSort / 1e6);
  } else {
    out += "  schedule            fifo: rays in the order they come\n";
  }
  if (memory.kind == mem::MemoryKind::Fixed) {
    return out + fmt::format("  memory              fixed, {} cycles (+0..{} jitter)\n", memory.fixedLatency,
                             memory.fixedJitter);
  }
  out += fmt::format("  memory              L1 {} KiB x3 per unit, hit rate {:.1f}%; L2 {} KiB, hit rate {:.1f}%; "
                     "DRAM {:g} GB/s\n",
                     memory.l1.kib, 100.0 * stats.l1Total().hitRate(), memory.l2.kib, 100.0 * stats.l2.hitRate(),
                     memory.dram.gbps);
  out += fmt::format("  DRAM                {:.1f} MB, {:.0f} bytes/ray, {:.2f} GB/s used ({:.0f}% of the bandwidth); "
                     "footprint {:.0f} bytes/ray\n",
                     double(stats.dramBytes) / 1e6, r.dramBytesPerRay, r.dramGbps, 100.0 * r.dramGbps / memory.dram.gbps,
                     r.footprintBytesPerRay);
  out += fmt::format("  stalls (cycles)     L1 full {}, L2 bank {}, L2 MSHRs {}, DRAM queue full {}, DRAM queued {}\n",
                     stats.l1FullCycles, stats.l2BankWaitCycles, stats.l2MshrFullCycles, stats.dramQueueFullCycles,
                     stats.dramQueueWaitCycles);
  return out;
}

}  // namespace lancer
