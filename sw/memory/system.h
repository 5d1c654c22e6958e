#pragma once

// The memory system of a chip: every unit's three read ports (node, index,
// triangle), served cycle by cycle. One implementation for every model of
// the units (the Verilated devices and the SystemC models call the same
// object), so a chip gives the same cycles whichever model runs its units.
//
// The cycle protocol, for each cycle of the chip:
//   1. each unit takes the responses of this cycle (response(), at most one
//      per port, in request order per port),
//   2. each unit offers its requests: request() if ready() (decided at the
//      previous tick()), else blocked(),
//   3. tick(): the memory's own work of the cycle, then the next cycle.
// Steps 1 and 2 touch only the calling unit's state, so units may run them
// on threads of their own; tick() runs alone, and everything shared (the L2,
// DRAM) moves only there, in unit order: runs are deterministic.

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "memory/address_map.h"
#include "memory/config.h"

namespace lancer::mem {

// What the memory system did, summed over a run.
struct MemoryStats {
  struct Cache {
    uint64_t accesses = 0;  // line lookups (a read spanning two lines is two)
    uint64_t hits = 0;
    uint64_t misses = 0;    // primary misses: a request to the next level
    uint64_t merges = 0;    // misses to a line already in flight: no new request
    double hitRate() const { return accesses ? double(hits) / double(accesses) : 0.0; }
    Cache& operator+=(const Cache& o);
  };
  // Per unit, per port (Port order); empty for the fixed model.
  std::vector<std::array<Cache, kPorts>> l1;
  Cache l2;
  uint64_t reads = 0;          // requests the units made
  uint64_t dramLines = 0;      // lines DRAM returned
  uint64_t dramBytes = 0;       // the caches' lines and the transfers'
  uint64_t transferBytes = 0;   // of them, transfer()'s (the ray queues' overflow)
  // The lines of the image the units read, each counted once per run: a run's
  // footprint. No schedule of the run's rays reads fewer from DRAM than its
  // footprint less what the caches held when it began (docs/scheduling.md).
  uint64_t footprintLines = 0;
  uint64_t footprintBytes = 0;
  // Stall causes, in cycles summed over what waited:
  uint64_t l1FullCycles = 0;       // a unit's request refused: its L1 had no free MSHR or queue entry
  uint64_t l2BankWaitCycles = 0;   // line requests waiting behind another in an L2 bank
  uint64_t l2MshrFullCycles = 0;   // an L2 bank's miss waiting for a free MSHR
  uint64_t dramQueueFullCycles = 0;  // an L2 bank's miss waiting for room in a DRAM channel's queue
  uint64_t dramQueueWaitCycles = 0;  // DRAM requests queued behind others (bandwidth)

  Cache l1Total() const;  // every L1 of every unit
  MemoryStats& operator+=(const MemoryStats& o);  // consecutive runs
};

void to_json(nlohmann::json& j, const MemoryStats& s);

class MemorySystem {
 public:
  virtual ~MemorySystem() = default;

  // The model `config` names, for `units` units reading the image laid out by
  // `map` (config validated by the caller).
  static std::unique_ptr<MemorySystem> make(const MemoryConfig& config, const AddressMap& map, int units);

  uint64_t cycle() const { return now_; }
  int units() const { return units_; }

  // Whether `port` of `unit` accepts a request in this cycle.
  virtual bool ready(int unit, Port port) const = 0;
  // A request of this cycle (only when ready): `record` is the port's record
  // index (the unit's address), `tag` comes back with the response.
  virtual void request(int unit, Port port, uint32_t record, uint32_t tag) = 0;
  // The response delivered on `port` in this cycle, if any.
  virtual bool response(int unit, Port port, uint32_t& record, uint32_t& tag) = 0;
  // The unit had a request on `port` this cycle but the port was not ready.
  virtual void blocked(int unit, Port port) = 0;
  // Bytes moved between the chip and DRAM outside the caches (the ray
  // queues' overflow, memory/ray_queues.h), from this cycle: in lines over the
  // DRAM channels, behind their work and ahead of later misses. Returns the
  // cycle by which the last line has moved. (Called between cycles, alone.)
  virtual uint64_t transfer(uint64_t bytes) = 0;
  // The end of this cycle.
  virtual void tick() = 0;
  // Nothing in flight anywhere.
  virtual bool idle() const = 0;
  // What it did since it was made or since clearStats().
  virtual MemoryStats stats() const = 0;
  virtual void clearStats() = 0;

 protected:
  explicit MemorySystem(int units) : units_(units) {}
  uint64_t now_ = 0;
  int units_;
};

}  // namespace lancer::mem
