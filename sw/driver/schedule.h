#pragma once

// The order in which a chip's dispatcher hands out a job's rays
// (docs/scheduling.md). `fifo` hands them out as they come; `sorted` orders a
// wave by a key of its rays first; `treelet` has the units set walks aside
// where they leave a treelet block and hands them out again block by block
// from the ray queues (memory/ray_queues.h). A schedule changes only which
// rays meet in the units and the caches at once: every ray is the same ray,
// walked the same way, so its hit, its visits and its tests are the same
// under any schedule.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "driver/quantize.h"
#include "memory/config.h"

namespace lancer {

enum class Schedule { Fifo, Sorted, Treelet };

std::string_view toString(Schedule schedule);
// Whether the schedule orders a job's rays by rayOrderKey before they are
// handed out (sorted; treelet launches its fresh rays in that order too), and
// so pays the sort (SortCost).
constexpr bool sortsRays(Schedule schedule) { return schedule != Schedule::Fifo; }
// Throws InputError naming --schedule and the schedules for an unknown name.
Schedule parseSchedule(std::string_view name);
std::vector<std::string> scheduleNames();

// The `sorted` schedule's key of a ray: the Morton code of its origin's top
// kSortOriginBits bits per axis (x the most significant of each triple), then
// its direction octant (3 bits, the least significant). Rays with a key in
// common leave nearby points toward the same octant, and so tend to enter the
// same nodes first; rays of neighbouring keys start near each other, so a run
// of the chip covers a compact region of the scene (an octant-major key, which
// spreads each run's rays over the whole scene, read more DRAM than fifo:
// docs/scheduling.md).
inline constexpr int kSortOriginBits = 10;
inline constexpr int kSortKeyBits = 3 + 3 * kSortOriginBits;
uint64_t rayOrderKey(const fx::QRay& ray);

// The indices of `rays`' lattice rays (nullopt ones left out) in the order
// `schedule` hands them to the chip: by index for fifo; by (rayOrderKey,
// index) for sorted and treelet (sortsRays), so the order is a function of
// the rays alone.
std::vector<uint32_t> dispatchOrder(Schedule schedule, std::span<const std::optional<QuantizedRay>> rays);

// What ordering the rays costs. The host's time is measured; a chip's is
// estimated (it is not simulated): a radix sort engine of kSortLanes lanes,
// each taking one {key, index} record a cycle, kSortPasses passes of
// kSortDigitBits-bit digits; the keys written to DRAM once and every pass
// reading and writing them there, the rays written once in their spawn order
// and read once in key order (a fifo chip streams them from the shaders to the
// units instead).
inline constexpr int kSortDigitBits = 11;
inline constexpr int kSortPasses = (kSortKeyBits + kSortDigitBits - 1) / kSortDigitBits;
inline constexpr int kSortLanes = 4;
inline constexpr uint32_t kSortRecordBytes = 8;  // {33-bit key, 31-bit index in the wave}

struct SortCost {
  uint64_t rays = 0;        // rays ordered
  uint64_t sorts = 0;       // jobs ordered (a class of a wave each)
  double hostSeconds = 0;   // the host's sort (measured)
  uint64_t chipCycles = 0;  // a chip's sort (estimated, above)
  uint64_t dramBytes = 0;   // and its DRAM traffic

  SortCost& operator+=(const SortCost& o);
  bool operator==(const SortCost&) const = default;
};

// The chip's estimate for a wave of `rays` rays on `memory` (its DRAM
// bandwidth and clock): the larger of the engine's cycles (passes x rays /
// lanes) and the cycles its DRAM bytes take at the bandwidth.
SortCost chipSortCost(uint64_t rays, const mem::MemoryConfig& memory);

void to_json(nlohmann::json& j, const SortCost& cost);

}  // namespace lancer
