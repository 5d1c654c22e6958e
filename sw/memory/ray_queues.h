#pragma once

// The treelet schedule's ray queues (docs/scheduling.md, "The treelet
// schedule"): walks a unit set aside where they left their treelet block wait
// in per-block queues in an on-chip queue memory, and the dispatcher hands the
// units the rays of one block at a time, so that the block's nodes and
// triangles are read while the rays that need them are together.
//
// The queue memory is modelled in cycles and bytes: a suspended walk's record
// (the ray and its bvh_walk_t, stored in whole words) is written through its
// write port and read back through its read port, each `bytesPerCycle` wide;
// when it has no room the record goes to DRAM instead (its write and its read
// share the DRAM channels with the caches: MemorySystem::transfer) and counts
// as overflow. Fresh rays come from the ray generator as in fifo, not from the
// queue memory.
//
// Which queue the units work on (pick()): the block the dispatcher is on, while
// its queue holds rays; else fresh rays while the queue memory is less full
// than `launchBelow`; else the fullest queue (ties: the lowest block); else
// the fresh rays left. So the queues fill before a block is worked on: the
// more rays wait for a block, the more share its nodes' trip from DRAM. Everything happens in endCycle's single thread, in unit order:
// runs are deterministic.

#include <cstdint>
#include <deque>
#include <map>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "memory/system.h"

namespace lancer::mem {

struct RayQueueConfig {
  int kib = 512;            // the on-chip queue memory
  int bytesPerCycle = 256;  // its write port's width, and its read port's (4 banks of 64 bytes)
  int wordBytes = 16;       // a record occupies whole words
  // Fresh rays are launched while the queue memory is less full than this;
  // above it the units work on the fullest queue (docs/scheduling.md).
  double launchBelow = 0.75;
  // Throws InputError naming --queue-kib, --queue-bytes-per-cycle or --queue-launch-below.
  void validate() const;
};
void to_json(nlohmann::json& j, const RayQueueConfig& c);

// What the queues did over a run.
struct RayQueueStats {
  uint64_t launched = 0;        // fresh rays handed out
  uint64_t suspensions = 0;     // walks set aside (each is resumed once)
  uint64_t bytesWritten = 0;    // to the queue memory (records in whole words)
  uint64_t bytesRead = 0;       // from it
  uint64_t overflows = 0;       // records that found no room on chip: to DRAM and back
  uint64_t overflowBytes = 0;   // the DRAM bytes they moved (written and read)
  uint64_t peakBytes = 0;       // the most the queue memory held at once
  uint64_t byteCycles = 0;      // its bytes summed over the cycles (the mean occupancy)
  uint64_t cycles = 0;
  uint64_t blockSwitches = 0;   // times the dispatcher turned to another block's queue
  uint64_t writeWaitCycles = 0; // records waiting for the write port, summed
  uint64_t readWaitCycles = 0;  // records waiting for the read port, summed
  RayQueueStats& operator+=(const RayQueueStats& o);
  bool operator==(const RayQueueStats&) const = default;
};
void to_json(nlohmann::json& j, const RayQueueStats& s);

class RayQueues {
 public:
  // `fresh` rays (segment ids 0..fresh-1) wait for launch; `memory` serves
  // the overflow's DRAM traffic and gives the cycle.
  RayQueues(const RayQueueConfig& config, size_t fresh, MemorySystem& memory);

  // A walk suspended in this cycle: segment `segment` waits for block
  // `block`, its record `bits` long.
  void suspend(size_t segment, uint32_t block, int bits);
  // Up to `count` segments for a unit, each with the cycle it may be offered
  // (its record read from the queue memory or DRAM; a fresh ray at once).
  struct Handed {
    size_t segment;
    uint64_t readyAt;
  };
  void handOut(size_t count, std::vector<Handed>& out);
  // The end of a cycle: records whose write finished join their queues.
  void endCycle();
  // Nothing waiting, nothing on its way.
  bool empty() const;
  const RayQueueStats& stats() const { return stats_; }

 private:
  struct Record {
    size_t segment;
    uint32_t block;
    uint64_t bytes;          // in the queue memory (0: in DRAM)
    uint64_t readyAt;        // its write is done
    uint64_t dramBytes = 0;  // in DRAM instead (overflow)
  };
  uint64_t recordBytes(int bits) const;
  bool pick();  // the queue to work on; false: none holds a ray

  RayQueueConfig config_;
  MemorySystem& memory_;
  size_t fresh_, launched_ = 0;
  std::multimap<uint64_t, Record> writing_;     // by the cycle their write is done
  std::map<uint32_t, std::deque<Record>> queues_;  // block -> records, oldest first
  size_t waiting_ = 0;                          // records in queues_
  bool onBlock_ = false;
  uint32_t block_ = 0;  // the block the units work on (onBlock_)
  uint64_t onChip_ = 0; // bytes the queue memory holds (written or being written, not yet read)
  uint64_t writeFree_ = 0, readFree_ = 0;  // the cycle each port is free
  RayQueueStats stats_;
};

}  // namespace lancer::mem
