// The chip's memory system (memory/): the cache tags against a plain LRU
// model replaying the same address trace; the hierarchy under contention from
// many units with random sizes and latencies (every request answered once, in
// order per port, with its tag; the counters balance); determinism; the
// fixed model equal to the single-unit ports; the timing of one miss; and the
// one-line errors of impossible configurations.

#include <gtest/gtest.h>

#include <deque>
#include <list>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "golden/stimulus.h"
#include "memory/address_map.h"
#include "memory/cache.h"
#include "memory/ray_queues.h"
#include "memory/system.h"

namespace lancer::mem {
namespace {

// The plain model: per set a list, most recently used first.
class ReferenceLru {
 public:
  ReferenceLru(int sets, int ways) : sets_(size_t(sets)), ways_(size_t(ways)) {}
  bool access(uint64_t line) {
    std::list<uint64_t>& set = sets_[line % sets_.size()];
    for (auto it = set.begin(); it != set.end(); ++it) {
      if (*it == line) {
        set.splice(set.begin(), set, it);
        return true;
      }
    }
    set.push_front(line);
    if (set.size() > ways_) set.pop_back();
    return false;
  }

 private:
  std::vector<std::list<uint64_t>> sets_;
  size_t ways_;
};

TEST(CacheTags, HitsAndMissesEqualAPlainLruOnEveryAccess) {
  struct Shape {
    int kib, ways, line;
  };
  for (const Shape shape : {Shape{1, 1, 64}, Shape{4, 2, 32}, Shape{16, 4, 64}, Shape{8, 8, 128}, Shape{2, 32, 64}}) {
    CacheTags tags(uint64_t(shape.kib) * 1024, shape.ways, shape.line);
    ReferenceLru reference(tags.sets(), shape.ways);
    std::mt19937_64 rng(uint64_t(shape.kib * 131 + shape.ways));
    // A mix of a hot set of lines (reuse) and a wide range (conflicts, capacity).
    const uint64_t lines = uint64_t(shape.kib) * 1024 / uint64_t(shape.line);
    int hits = 0;
    for (int i = 0; i < 200000; ++i) {
      const uint64_t line = rng() % 4 == 0 ? rng() % (8 * lines) : rng() % (lines / 2 + 1);
      const bool expected = reference.access(line);
      bool hit = tags.lookup(line);
      if (!hit) tags.insert(line);
      ASSERT_EQ(hit, expected) << "access " << i << " line " << line << " (" << shape.kib << " KiB, " << shape.ways
                               << " ways)";
      hits += hit;
    }
    EXPECT_GT(hits, 1000);  // the trace exercised hits, not only misses
    EXPECT_LT(hits, 199000);
  }
}

// Regions of the shapes the units read: 4-byte cells, 4-byte indices, 27-byte triangles.
AddressMap smallMap(uint64_t records = 5000, uint32_t nodeBytes = 4, uint32_t group = 1) {
  return AddressMap({Region{"node table", 0, nodeBytes, group, records}, Region{"index list", 0, 4, 1, records},
                     Region{"triangle table", 0, 27, 1, records}, Region{"quadric table", 0, 68, 1, 0}});
}

MemoryConfig hierarchy() {
  MemoryConfig c;
  c.kind = MemoryKind::Hierarchy;
  c.clockMhz = 700;
  return c;
}

struct Outstanding {
  uint32_t record, tag;
};

// Drives `units` units that each request on every port with probability
// `rate` per cycle (when ready) for `cycles` cycles, then drains. Checks every
// response against the port's oldest outstanding request; returns the cycle
// of each response, in order, for the determinism test.
std::vector<uint64_t> drive(MemorySystem& memory, int units, double rate, int cycles, uint64_t records, uint64_t seed,
                            uint64_t* requests = nullptr) {
  std::mt19937_64 rng(seed);
  std::vector<std::array<std::deque<Outstanding>, kPorts>> pending(static_cast<size_t>(units));
  std::vector<uint64_t> when;
  uint64_t issued = 0;
  std::uniform_real_distribution<double> coin(0, 1);
  for (int c = 0; ; ++c) {
    bool busy = false;
    for (int u = 0; u < units; ++u) {
      for (int p = 0; p < kPorts; ++p) {
        uint32_t record = 0, tag = 0;
        if (memory.response(u, Port(p), record, tag)) {
          auto& q = pending[size_t(u)][size_t(p)];
          EXPECT_FALSE(q.empty()) << "a response nobody asked for: unit " << u << " port " << p;
          if (q.empty()) return when;
          EXPECT_EQ(record, q.front().record) << "unit " << u << " port " << p << " cycle " << c;
          EXPECT_EQ(tag, q.front().tag);
          q.pop_front();
          when.push_back(memory.cycle());
        }
        if (c < cycles && coin(rng) < rate) {
          // Hot records most of the time, so that the caches hit and merge.
          const uint32_t record = uint32_t(coin(rng) < 0.7 ? rng() % 64 : rng() % records);
          const uint32_t tag = uint32_t(rng() % 32);
          if (memory.ready(u, Port(p))) {
            memory.request(u, Port(p), record, tag);
            pending[size_t(u)][size_t(p)].push_back({record, tag});
            ++issued;
          } else {
            memory.blocked(u, Port(p));
          }
        }
        busy |= !pending[size_t(u)][size_t(p)].empty();
      }
    }
    memory.tick();
    if (c >= cycles && !busy) break;
    if (c > cycles + 2000000) {
      ADD_FAILURE() << "the memory system did not drain";
      break;
    }
  }
  EXPECT_TRUE(memory.idle());
  if (requests) *requests = issued;
  return when;
}

TEST(HierarchyMemory, EveryRequestAnsweredOnceInOrderAndTheCountersBalance) {
  std::mt19937_64 rng(7);
  MemoryStats all;  // over the trials: every kind of contention happened
  for (int trial = 0; trial < 12; ++trial) {
    MemoryConfig c = hierarchy();
    c.l1.kib = 1 << (rng() % 4);  // 1..8 KiB: plenty of misses
    c.l1.ways = 1 << (rng() % 3);
    c.l1.lineBytes = 32 << (rng() % 3);
    c.l1.mshrs = 4 + int(rng() % 8);
    c.l1.hitLatency = 1 + int(rng() % 4);
    c.l2.kib = 16 << (rng() % 4);
    c.l2.banks = 1 << (rng() % 4);
    c.l2.latency = 1 + int(rng() % 20);
    c.l2.mshrs = 1 + int(rng() % 16);
    c.dram.gbps = 1.0 + double(rng() % 30);
    c.dram.latencyNs = double(rng() % 100);
    c.dram.channels = 1 << (rng() % 3);
    c.dram.queueDepth = 1 + int(rng() % 8);
    c.validate();
    const int units = 1 + int(rng() % 16);
    const AddressMap map = smallMap(20000);
    auto memory = MemorySystem::make(c, map, units);
    uint64_t requests = 0;
    const std::vector<uint64_t> when = drive(*memory, units, 0.6, 3000, 20000, uint64_t(trial), &requests);
    ASSERT_EQ(when.size(), requests) << "trial " << trial;

    const MemoryStats s = memory->stats();
    EXPECT_EQ(s.reads, requests);
    ASSERT_EQ(s.l1.size(), size_t(units));
    const MemoryStats::Cache l1 = s.l1Total();
    EXPECT_EQ(l1.accesses, l1.hits + l1.misses + l1.merges);
    EXPECT_GE(l1.accesses, requests);  // a triangle may span two lines
    // Every L1 miss is one L2 access; every L2 miss one DRAM line.
    EXPECT_EQ(s.l2.accesses, l1.misses);
    EXPECT_EQ(s.l2.accesses, s.l2.hits + s.l2.misses + s.l2.merges);
    EXPECT_EQ(s.dramLines, s.l2.misses);
    EXPECT_EQ(s.dramBytes, s.dramLines * uint64_t(c.l1.lineBytes));
    // The footprint: each line read counted once; a cold system read each from DRAM at least once.
    EXPECT_GT(s.footprintLines, 0u);
    EXPECT_LE(s.footprintLines, l1.misses);
    EXPECT_LE(s.footprintLines, s.dramLines);
    EXPECT_EQ(s.footprintBytes, s.footprintLines * uint64_t(c.l1.lineBytes));
    EXPECT_GT(l1.hits, 0u);
    EXPECT_GT(s.l2.misses, 0u);
    all += s;
  }
  EXPECT_GT(all.l1FullCycles, 0u);
  EXPECT_GT(all.l2BankWaitCycles, 0u);
  EXPECT_GT(all.l2MshrFullCycles, 0u);
  EXPECT_GT(all.dramQueueFullCycles, 0u);
  EXPECT_GT(all.dramQueueWaitCycles, 0u);
  EXPECT_GT(all.l1Total().merges, 0u);
  EXPECT_GT(all.l2.merges, 0u);
}

TEST(HierarchyMemory, ASeedlessRunIsTheSameTwice) {
  MemoryConfig c = hierarchy();
  c.l1.kib = 2;
  c.l2.kib = 64;
  const AddressMap map = smallMap(20000);
  auto a = MemorySystem::make(c, map, 8);
  auto b = MemorySystem::make(c, map, 8);
  const auto first = drive(*a, 8, 0.5, 4000, 20000, 3);
  const auto second = drive(*b, 8, 0.5, 4000, 20000, 3);
  EXPECT_EQ(first, second);
  EXPECT_EQ(nlohmann::json(a->stats()).dump(), nlohmann::json(b->stats()).dump());
}

// One read, cold: L1 tag check, the L2 bank, DRAM (latency and one line's
// transfer on its channel), back through the L2, the L1 fill, the response.
// A hierarchy of round figures: 1 ns cycles, L1 hits in 2, the L2 in 10, DRAM
// in 40 ns plus 2 ns a 64-byte line on each of its 2 channels.
MemoryConfig roundHierarchy() {
  MemoryConfig c = hierarchy();
  c.clockMhz = 1000;
  c.l1.hitLatency = 2;
  c.l2.latency = 10;
  c.dram.latencyNs = 40;
  c.dram.gbps = 64;
  c.dram.channels = 2;
  return c;
}

// The cycle in which one index read (record 0, tag 5) asked now is answered.
uint64_t answerOfOneRead(MemorySystem& memory, uint32_t& record, uint32_t& tag) {
  memory.request(0, Port::Index, 0, 5);
  for (int i = 0; i < 200; ++i) {
    memory.tick();
    if (memory.response(0, Port::Index, record, tag)) return memory.cycle();
  }
  return 0;
}

TEST(HierarchyMemory, AColdReadTakesEveryLevelsLatency) {
  auto memory = MemorySystem::make(roundHierarchy(), smallMap(), 1);
  uint32_t record = 0, tag = 0;
  const uint64_t answered = answerOfOneRead(*memory, record, tag);
  // Lookup in the bank at cycle 2; DRAM done at 2 + 40 + 2 = 44 ns (cycle 44);
  // the fill reaches the L1 at 44 + 10 = 54 and answers in cycle 55.
  EXPECT_EQ(answered, 55u);
  EXPECT_EQ(tag, 5u);
  // The same line again: an L1 hit, hitLatency cycles.
  memory->tick();
  const uint64_t asked = memory->cycle();
  memory->request(0, Port::Index, 1, 6);  // the next index shares the line
  for (int i = 0; i < 10; ++i) {
    memory->tick();
    if (memory->response(0, Port::Index, record, tag)) break;
  }
  EXPECT_EQ(memory->cycle() - asked, 2u);
  EXPECT_EQ(record, 1u);
  EXPECT_EQ(memory->stats().l1Total().hits, 1u);
  // Two reads of one line: a footprint of one line, until the stats are cleared.
  EXPECT_EQ(memory->stats().footprintLines, 1u);
  EXPECT_EQ(memory->stats().footprintBytes, 64u);
  memory->clearStats();
  EXPECT_EQ(memory->stats().footprintLines, 0u);
  memory->request(0, Port::Triangle, 0, 7);
  EXPECT_GE(memory->stats().footprintLines, 1u);
}

// Unit 0 of the fixed model is the single-unit run's three ports.
TEST(FixedMemory, UnitZeroIsTheSingleUnitPorts) {
  MemoryConfig c;
  c.fixedLatency = 7;
  c.fixedJitter = 5;
  c.seed = 11;
  auto memory = MemorySystem::make(c, smallMap(), 3);
  std::array<fx::MemoryReadPort, kPorts> single;
  for (int p = 0; p < kPorts; ++p) single[size_t(p)].restart(7, 5, 11 * 3 + uint64_t(p) + 1);
  std::mt19937_64 rng(1);
  for (uint64_t cycle = 0; cycle < 5000; ++cycle) {
    for (int p = 0; p < kPorts; ++p) {
      uint32_t a1 = 0, t1 = 0, a2 = 0, t2 = 0;
      const bool r1 = memory->response(0, Port(p), a1, t1);
      const bool r2 = single[size_t(p)].respond(cycle, a2, t2);
      ASSERT_EQ(r1, r2) << "cycle " << cycle << " port " << p;
      if (r1) {
        EXPECT_EQ(a1, a2);
      }
      if (rng() % 2) {
        const uint32_t addr = uint32_t(rng() % 1000);
        memory->request(0, Port(p), addr, 1);
        single[size_t(p)].request(cycle, addr, 1);
        memory->request(1, Port(p), addr, 1);  // another unit's traffic changes nothing of unit 0's
      }
    }
    memory->tick();
  }
}

TEST(MemoryConfig, ImpossibleSettingsNameTheirOption) {
  const auto fails = [](auto edit, const std::string& option) {
    MemoryConfig c = hierarchy();
    edit(c);
    try {
      c.validate();
      ADD_FAILURE() << option << ": accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(option + " ", 0), 0u) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  };
  fails([](MemoryConfig& c) { c.l1.kib = 0; }, "--l1-kib");
  fails([](MemoryConfig& c) { c.l1.lineBytes = 2048; c.l1.kib = 1; }, "--l1-kib");  // smaller than a line
  fails([](MemoryConfig& c) { c.l1.kib = 12; }, "--l1-kib");                          // 48 sets
  fails([](MemoryConfig& c) { c.l1.lineBytes = 48; }, "--l1-line-bytes");
  fails([](MemoryConfig& c) { c.l1.ways = 0; }, "--l1-ways");
  fails([](MemoryConfig& c) { c.l2.kib = 768; }, "--l2-kib");                         // 1536 sets
  fails([](MemoryConfig& c) { c.l2.banks = 3; }, "--l2-banks");
  fails([](MemoryConfig& c) { c.dram.gbps = 0; }, "--dram-gbps");
  fails([](MemoryConfig& c) { c.dram.gbps = -3; }, "--dram-gbps");
  fails([](MemoryConfig& c) { c.dram.channels = 6; }, "--dram-channels");
  fails([](MemoryConfig& c) { c.dram.latencyNs = -1; }, "--dram-latency-ns");
  fails([](MemoryConfig& c) { c.kind = MemoryKind::Fixed; c.fixedLatency = 0; }, "--mem-latency");
  EXPECT_THROW(parseMemoryKind("cached"), InputError);
}

TEST(AddressMap, AnImagePastTheAddressWidthIsAnError) {
  try {
    smallMap(uint64_t(1) << 29, 8, 8);  // 4 GiB of nodes
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("32-bit address space"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("node table"), std::string::npos) << e.what();
  }
  const AddressMap map = smallMap(1000);
  EXPECT_EQ(map.region(Port::Node).base, AddressMap::kBase);
  EXPECT_EQ(map.region(Port::Index).base % AddressMap::kPageBytes, 0u);
  EXPECT_GE(map.region(Port::Index).base, map.region(Port::Node).base + 4000);
  EXPECT_EQ(map.span(Port::Triangle, 3).first, map.region(Port::Triangle).base + 81);
}

TEST(HierarchyMemory, TooFewMshrsForARecordIsAnError) {
  MemoryConfig c = hierarchy();
  c.l1.mshrs = 2;
  c.l1.lineBytes = 32;
  EXPECT_THROW(MemorySystem::make(c, smallMap(1000, 16, 8), 1), InputError);  // 128-byte groups: 5 lines
}

// A transfer (the ray queues' overflow) moves its bytes in lines over the DRAM
// channels: it takes their bandwidth and latency, counts in the DRAM bytes, and
// a miss after it waits behind it.
TEST(HierarchyMemory, ATransferTakesTheDramChannelsAndAMissWaitsBehindIt) {
  auto memory = MemorySystem::make(roundHierarchy(), smallMap(), 1);
  // 20 lines over two channels: 10 each, 2 ns apart; the last done at 18 + 40 + 2.
  EXPECT_EQ(memory->transfer(20 * 64), 60u);
  EXPECT_EQ(memory->stats().transferBytes, 20u * 64);
  EXPECT_EQ(memory->stats().dramBytes, 20u * 64);
  // The cold read of AColdReadTakesEveryLevelsLatency (answered in cycle 55)
  // now finds its channel busy until 20 ns.
  uint32_t record = 0, tag = 0;
  EXPECT_EQ(answerOfOneRead(*memory, record, tag), 55u + 18u);
  // The fixed model has no DRAM: a transfer takes its latency, and is counted.
  MemoryConfig fixed;
  fixed.fixedLatency = 7;
  auto flat = MemorySystem::make(fixed, smallMap(), 1);
  EXPECT_EQ(flat->transfer(100), 7u);
  EXPECT_EQ(flat->stats().transferBytes, 100u);
}

// The treelet schedule's ray queues (memory/ray_queues.h): fresh rays first,
// then the fullest block's queue; every walk handed out once; the ports' bytes
// per cycle; records without room on chip to DRAM and back.
TEST(RayQueues, FreshRaysFirstThenTheFullestBlockEachWalkOnce) {
  MemoryConfig c;  // fixed latency 20
  auto memory = MemorySystem::make(c, smallMap(), 1);
  RayQueueConfig q;
  q.kib = 1;
  q.bytesPerCycle = 16;
  q.wordBytes = 16;
  q.launchBelow = 0.5;
  RayQueues queues(q, 6, *memory);
  std::vector<RayQueues::Handed> out;
  queues.handOut(4, out);
  ASSERT_EQ(out.size(), 4u);
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(out[i].segment, i);
  EXPECT_EQ(out[0].readyAt, 0u);  // fresh rays come from the ray generator
  // Walks 10..14 suspended in cycle 0: a 16-byte record each (100 bits), one
  // cycle each on the write port; blocks 7 (three walks) and 3 (two).
  queues.suspend(10, 7, 100);
  queues.suspend(11, 3, 100);
  queues.suspend(12, 7, 100);
  queues.suspend(13, 3, 100);
  queues.suspend(14, 7, 100);
  EXPECT_EQ(queues.stats().writeWaitCycles, 0u + 1 + 2 + 3 + 4);
  for (int i = 0; i < 6; ++i) {  // the last write is done at the end of cycle 5
    queues.endCycle();
    memory->tick();
  }
  // 80 bytes on chip, below half of 1 KiB: the fresh rays left come first.
  queues.handOut(4, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].segment, 4u);
  EXPECT_EQ(out[1].segment, 5u);
  // Then the fullest block, 7, oldest first; each record read through the
  // read port, a cycle each.
  queues.handOut(2, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].segment, 10u);
  EXPECT_EQ(out[1].segment, 12u);
  EXPECT_EQ(out[0].readyAt, memory->cycle() + 1);
  EXPECT_EQ(out[1].readyAt, memory->cycle() + 2);
  // The dispatcher stays on block 7 while it holds a walk, though block 3 is fuller now.
  queues.handOut(4, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].segment, 14u);
  queues.handOut(4, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].segment, 11u);
  EXPECT_EQ(out[1].segment, 13u);
  EXPECT_TRUE(queues.empty());
  queues.handOut(4, out);
  EXPECT_TRUE(out.empty());
  const RayQueueStats& s = queues.stats();
  EXPECT_EQ(s.launched, 6u);
  EXPECT_EQ(s.suspensions, 5u);
  EXPECT_EQ(s.bytesWritten, 5u * 16);
  EXPECT_EQ(s.bytesRead, s.bytesWritten);
  EXPECT_EQ(s.peakBytes, 5u * 16);
  EXPECT_EQ(s.blockSwitches, 2u);
  EXPECT_EQ(s.overflows, 0u);
}

TEST(RayQueues, ARecordWithoutRoomOnChipGoesToDramAndBack) {
  MemoryConfig c = hierarchy();
  auto memory = MemorySystem::make(c, smallMap(), 1);
  RayQueueConfig q;
  q.kib = 1;
  RayQueues queues(q, 0, *memory);
  queues.suspend(0, 1, 8 * 600);  // 608 bytes in 16-byte words: on chip
  queues.suspend(1, 1, 8 * 600);  // no room left: DRAM
  EXPECT_EQ(queues.stats().overflows, 1u);
  EXPECT_EQ(queues.stats().bytesWritten, 608u);
  for (int i = 0; i < 1000; ++i) {
    queues.endCycle();
    memory->tick();
  }
  std::vector<RayQueues::Handed> out;
  queues.handOut(2, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_GT(out[1].readyAt, out[0].readyAt);  // from DRAM, after the latency
  const RayQueueStats& s = queues.stats();
  EXPECT_EQ(s.overflowBytes, 2u * 608);  // written and read back
  EXPECT_EQ(memory->stats().transferBytes, 2u * 640);  // in whole 64-byte lines
  EXPECT_EQ(s.bytesRead, 608u);
  EXPECT_TRUE(queues.empty());
}

TEST(RayQueueConfig, ImpossibleSettingsNameTheirOption) {
  const auto message = [](auto change) {
    RayQueueConfig q;
    change(q);
    try {
      q.validate();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message([](RayQueueConfig& q) { q.kib = 0; }), "--queue-kib 0: use 1..1048576");
  EXPECT_EQ(message([](RayQueueConfig& q) { q.bytesPerCycle = 0; }), "--queue-bytes-per-cycle 0: use 1..4096");
  EXPECT_EQ(message([](RayQueueConfig& q) { q.launchBelow = 1.5; }),
            "--queue-launch-below 1.5: a fraction of the queue memory, in (0, 1]");
  EXPECT_EQ(message([](RayQueueConfig&) {}), "no error");
}

}  // namespace
}  // namespace lancer::mem
