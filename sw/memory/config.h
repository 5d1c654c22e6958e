#pragma once

// The memory system behind a chip's traversal units (docs/chip.md): which
// model (`fixed` latency, or the `hierarchy` of L1s, a shared L2 and DRAM) and
// every size and latency of it. One struct, so a run's report states the
// memory it ran on; validate() names the option of anything impossible.

#include <cstdint>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace lancer::mem {

enum class MemoryKind { Fixed, Hierarchy };

// A unit's three read ports, in the order of the unit's interface.
enum class Port : int { Node = 0, Index = 1, Triangle = 2 };
inline constexpr int kPorts = 3;
const char* portName(Port port);

// Each of a unit's three L1s (one per read port, docs/chip.md "Why three L1s").
struct L1Config {
  int kib = 16;         // capacity of each of the unit's three L1s
  int ways = 4;
  int lineBytes = 64;   // the line of the whole hierarchy (L2 and DRAM move lines too)
  int mshrs = 8;        // lines in flight to the L2 per L1 (a miss to a line in flight merges)
  int hitLatency = 2;   // cycles from a request to its response on a hit
};

// The L2 shared by every unit, banked by line address.
struct L2Config {
  int kib = 1024;
  int ways = 8;
  int banks = 8;        // each bank takes one lookup per cycle
  int latency = 12;     // cycles from a bank's lookup to the fill leaving for the L1
  int mshrs = 16;       // lines in flight to DRAM per bank
};

// DRAM: channels interleaved by line, each a queue served in order at its
// share of the bandwidth.
struct DramConfig {
  double gbps = 12.8;       // total bandwidth, GB/s (10^9 bytes per second)
  double latencyNs = 50.0;  // from the channel starting a request to the first byte back
  int channels = 2;
  int queueDepth = 16;      // requests waiting per channel
};

struct MemoryConfig {
  MemoryKind kind = MemoryKind::Fixed;
  // kind == Fixed: today's single-unit model, per port (golden/stimulus.h).
  int fixedLatency = 20;
  int fixedJitter = 0;
  // kind == Hierarchy:
  L1Config l1;
  L2Config l2;
  DramConfig dram;
  double clockMhz = 500.0;  // the chip's clock, converting DRAM's nanoseconds into cycles
  uint64_t seed = 1;        // the fixed model's jitter; the hierarchy draws nothing

  // Throws InputError naming the option (--l1-kib ...) of an impossible setting.
  void validate() const;
};

// The seed of unit u's draws (its stream stimulus, its fixed memory ports):
// unit 0 keeps the run's seed, so a chip of one unit draws as a single unit did.
inline uint64_t unitSeed(uint64_t seed, int unit) { return seed + uint64_t(unit) * 0x9E37'79B9'7F4A'7C15ull; }

// "fixed" / "hierarchy"; parseMemoryKind throws InputError for anything else.
const char* memoryKindName(MemoryKind kind);
MemoryKind parseMemoryKind(const std::string& name);

void to_json(nlohmann::json& j, const MemoryConfig& c);

}  // namespace lancer::mem
