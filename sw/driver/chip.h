#pragma once

// What a chip of N traversal units (docs/chip.md) adds around any model of a
// unit: where the unit's image lies in memory, the memory system a run uses,
// and the chip's figures for the summary and the report. The devices
// (Verilated, SystemC) clock their units, take rays from the dispatcher
// (memory/dispatcher.h) and call the memory system (memory/system.h) in the
// protocol it documents.

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "driver/schedule.h"
#include "driver/traversal_device.h"
#include "golden/unit.h"
#include "memory/address_map.h"
#include "memory/dispatcher.h"
#include "memory/system.h"

namespace lancer {

// A record's bytes in memory, and the bytes of one read of a unit's node port
// (kGroup records: the octree's child group).
constexpr uint32_t recordBytes(int bits) { return uint32_t((bits + 7) / 8); }
template <class Desc>
constexpr uint32_t nodeReadBytes() {
  return recordBytes(fx::kNodeBitsOf<Desc>) * uint32_t(Desc::kGroup);
}

// The regions of descriptor `Desc`'s image, in port order, not yet placed:
// its node table (records of the node's bits rounded up to bytes, kGroup of
// them per read), the index list (32-bit primitive entries), the triangle
// table (the triangle record's bits rounded up to bytes), then the quadric
// table (likewise; the triangle port reads it too).
template <class Desc>
std::array<mem::Region, mem::kRegions> regionsOf(const typename Desc::Image& image) {
  return {mem::Region{Desc::kNames.nodeTable, 0, recordBytes(fx::kNodeBitsOf<Desc>), uint32_t(Desc::kGroup),
                      uint64_t(Desc::nodes(image).size())},
          mem::Region{"index list", 0, 4, 1, uint64_t(image.indices.size())},
          mem::Region{"triangle table", 0, recordBytes(fx::kIsectTriBits), 1, uint64_t(image.triangles.size())},
          mem::Region{"quadric table", 0, recordBytes(fx::kIsectQuadricBits), 1, uint64_t(image.quadrics.size())}};
}

// The image of descriptor `Desc` in the chip's address space (regionsOf).
// InputError if it does not fit.
template <class Desc>
mem::AddressMap addressMapOf(const typename Desc::Image& image) {
  return mem::AddressMap(regionsOf<Desc>(image));
}

// The memory system a run of a device uses: the hardware path's
// (options.sharedMemory, warm) when it serves the run's units, else a new one
// kept in `own`; its statistics cleared for the run.
template <class Desc>
mem::MemorySystem& memoryFor(const TraversalRunOptions& options, const typename Desc::Image& image,
                             std::unique_ptr<mem::MemorySystem>& own) {
  mem::MemorySystem* memory = options.sharedMemory;
  if (memory == nullptr || memory->units() != options.units) {
    own = mem::MemorySystem::make(memoryConfigOf(options), addressMapOf<Desc>(image), options.units);
    memory = own.get();
  }
  memory->clearStats();
  return *memory;
}

// What a chip did over a job (or the jobs of a ray class, or of a run): its
// units' share of the work and its memory system's figures, for the summary
// and the report (docs/chip.md, "Report").
struct ChipFigures {
  mem::MemoryConfig memory;
  std::vector<uint64_t> unitRays, unitBusyCycles;  // per unit
  mem::MemoryStats stats;
  Schedule schedule = Schedule::Fifo;
  SortCost sort;  // schedule sorted: what ordering the rays cost
  fx::TreeletCrossings treelets;  // a treelet layout: what a treelet schedule would move (golden walk)
  uint64_t quadricTests = 0;      // the units' ray-quadric tests (their rt_quadric's work)
  mem::RayQueueConfig queueConfig;  // schedule treelet: the ray queues
  mem::RayQueueStats queues;

  int units() const { return int(unitRays.size()); }
  ChipFigures& operator+=(const ChipFigures& o);
  // `cycles` and `rays` of the same jobs; `clockHz` the run's clock.
  nlohmann::json toJson(uint64_t cycles, uint64_t rays, double clockHz) const;
  // The summary's lines, each starting with two spaces.
  std::string summary(uint64_t cycles, uint64_t rays, double clockHz) const;
};

}  // namespace lancer
