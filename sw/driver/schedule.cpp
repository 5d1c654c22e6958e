#include "driver/schedule.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "common/error.h"
#include "golden/formats.h"
#include "golden/records.h"

namespace lancer {

namespace {

constexpr Schedule kSchedules[] = {Schedule::Fifo, Schedule::Sorted, Schedule::Treelet};

// Bit i of v to bit 3i (v below 2^10).
uint64_t spreadBits(uint64_t v) {
  v &= 0x3ff;
  v = (v | (v << 16)) & 0x30000ff;
  v = (v | (v << 8)) & 0x300f00f;
  v = (v | (v << 4)) & 0x30c30c3;
  v = (v | (v << 2)) & 0x9249249;
  return v;
}
static_assert(kSortOriginBits == 10, "spreadBits spreads 10 bits");

// An origin coordinate's cell of the key: its top kSortOriginBits bits; a
// position narrower than that (8-bit formats) fills them from the top.
uint64_t originCell(uint64_t coordinate) {
  if constexpr (fx::kPosBits >= kSortOriginBits) {
    return coordinate >> (fx::kPosBits - kSortOriginBits);
  } else {
    return coordinate << (kSortOriginBits - fx::kPosBits);
  }
}

}  // namespace

std::string_view toString(Schedule schedule) {
  switch (schedule) {
    case Schedule::Fifo: return "fifo";
    case Schedule::Sorted: return "sorted";
    case Schedule::Treelet: return "treelet";
  }
  return "?";
}

std::vector<std::string> scheduleNames() {
  std::vector<std::string> names;
  for (Schedule s : kSchedules) names.emplace_back(toString(s));
  return names;
}

Schedule parseSchedule(std::string_view name) {
  for (Schedule s : kSchedules) {
    if (toString(s) == name) return s;
  }
  throw InputError(fmt::format("--schedule {}: no such schedule (available: {})", name, fmt::join(scheduleNames(), ", ")));
}


uint64_t rayOrderKey(const fx::QRay& ray) {
  uint64_t octant = 0, morton = 0;
  for (int a = 0; a < 3; ++a) {
    octant |= uint64_t(ray.dir[size_t(a)] < 0) << a;
    morton |= spreadBits(originCell(uint64_t(ray.org[size_t(a)]))) << (2 - a);
  }
  return (morton << 3) | octant;
}

std::vector<uint32_t> dispatchOrder(Schedule schedule, std::span<const std::optional<QuantizedRay>> rays) {
  std::vector<uint32_t> order;
  order.reserve(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    if (rays[i]) order.push_back(uint32_t(i));
  }
  if (sortsRays(schedule)) {
    std::vector<uint64_t> keyed(order.size());  // {key, index}: one 64-bit compare, ties by index
    for (size_t k = 0; k < order.size(); ++k) keyed[k] = (rayOrderKey(rays[order[k]]->q) << 31) | order[k];
    std::sort(keyed.begin(), keyed.end());
    for (size_t k = 0; k < order.size(); ++k) order[k] = uint32_t(keyed[k] & 0x7fff'ffffu);
  }
  return order;
}

SortCost& SortCost::operator+=(const SortCost& o) {
  *this = {rays + o.rays, sorts + o.sorts, hostSeconds + o.hostSeconds, chipCycles + o.chipCycles,
           dramBytes + o.dramBytes};
  return *this;
}

SortCost chipSortCost(uint64_t rays, const mem::MemoryConfig& memory) {
  constexpr uint64_t kRayBytes = uint64_t(fx::kIsectRayBits + 7) / 8;
  SortCost cost;
  cost.rays = rays;
  cost.sorts = 1;
  // The keys written once, every pass reading and writing them, the rays
  // written once and read once.
  cost.dramBytes = rays * (kSortRecordBytes * (1 + 2 * uint64_t(kSortPasses)) + 2 * kRayBytes);
  const double bytesPerCycle = memory.dram.gbps * 1e3 / memory.clockMhz;
  const auto dramCycles = uint64_t(std::ceil(double(cost.dramBytes) / bytesPerCycle));
  cost.chipCycles = std::max((rays * uint64_t(kSortPasses) + kSortLanes - 1) / kSortLanes, dramCycles);
  return cost;
}

void to_json(nlohmann::json& j, const SortCost& cost) {
  j = {{"rays", cost.rays}, {"sorts", cost.sorts}, {"host_seconds", cost.hostSeconds},
       {"chip_cycles_estimate", cost.chipCycles}, {"chip_dram_bytes_estimate", cost.dramBytes},
       {"key_bits", kSortKeyBits}, {"passes", kSortPasses}, {"lanes", kSortLanes}};
}

}  // namespace lancer
