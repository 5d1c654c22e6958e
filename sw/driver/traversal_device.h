#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "driver/isect_device.h"
#include "golden/trace.h"
#include "golden/units.h"
#include "memory/ray_queues.h"
#include "memory/system.h"

namespace lancer {

// How a run of a traversal unit (grid, octree) is driven.
struct TraversalRunOptions {
  StreamOptions stream;      // ray input bubbles, result/visit output stalls, seed, waveform
  int memLatency = 20;       // cycles from a memory request to its response (>= 1)
  int memLatencyJitter = 0;  // extra 0..jitter cycles per request, random (seeded); responses stay in order per port
  int raysInFlight = 0;      // ray slots to use; 0 = all the unit was built with
  // The chip (docs/chip.md): `units` copies of the unit share one memory system.
  int units = 1;             // 1..kMaxUnits
  int dispatchBatch = 32;    // consecutive rays the dispatcher hands a unit at once
  int hostThreads = 1;       // host threads clocking the units; 0: min(cores, units) (docs/chip.md, "How the host runs it")
  // The memory system: its kind, the hierarchy's sizes and the chip's clock
  // (for DRAM's nanoseconds). The fixed model's latency and jitter are
  // memLatency and memLatencyJitter above, its seed the stream's.
  mem::MemoryConfig memory;
  // The hierarchy of the hardware path, kept across its runs so that the
  // caches stay warm from batch to batch and wave to wave, as on a chip
  // tracing one frame (driver/job.cpp). Null: the run makes its own, empty.
  mem::MemorySystem* sharedMemory = nullptr;
  // The treelet schedule (docs/scheduling.md): the units set walks aside at
  // treelet blocks, and the ray queues hand the rays out block by block.
  bool treelets = false;
  mem::RayQueueConfig queues;
};

inline constexpr int kMaxUnits = 64;

// InputError naming the option for a chip `options` cannot describe: units
// outside 1..kMaxUnits, a dispatch batch below 1, negative host threads, or
// an impossible memory system.
void checkChipOptions(const TraversalRunOptions& options);

// The memory system `options` describe, complete (the fixed model's latency,
// jitter and seed filled in from the options' own fields).
inline mem::MemoryConfig memoryConfigOf(const TraversalRunOptions& options) {
  mem::MemoryConfig c = options.memory;
  c.fixedLatency = options.memLatency;
  c.fixedJitter = options.memLatencyJitter;
  c.seed = options.stream.seed;
  return c;
}

// Per-unit counts of consecutive runs, unit by unit (the longer list wins).
inline void addPerUnit(std::vector<uint64_t>& into, const std::vector<uint64_t>& more) {
  if (into.size() < more.size()) into.resize(more.size());
  for (size_t u = 0; u < more.size(); ++u) into[u] += more[u];
}

// What the unit did, in clock cycles of the simulated chip.
struct TraversalRunStats {
  uint64_t cycles = 0;           // first ray offered to last result taken
  uint64_t rays = 0;
  uint64_t steps = 0;            // cells (grid) or nodes (octree) entered, summed over rays
  uint64_t stepReadyCycles = 0;  // cycles in which some ray slot could take a step
  uint64_t nodeReads = 0;        // memory reads per region: cell table / child groups,
  uint64_t indexReads = 0;       // index list,
  uint64_t triangleReads = 0;    // triangle table (and quadric table: the same port)
  uint64_t isectTests = 0;       // pairs the intersection pipelines accepted
  uint64_t quadricTests = 0;     // of which ray-quadric (rt_quadric's)
  uint64_t isectBusyCycles = 0;  // cycles in which it accepted one
  bool cycleAccurate = true;     // false for the golden model (no timing)
  // The chip: per unit the rays it took and the cycles it had one in flight;
  // what the memory system did (empty for the golden model).
  std::vector<uint64_t> unitRays, unitBusyCycles;
  mem::MemoryStats memory;
  mem::RayQueueStats queues;  // the treelet schedule's

  uint64_t memoryReads() const { return nodeReads + indexReads + triangleReads; }
  // The stats of consecutive runs, as of one.
  TraversalRunStats& operator+=(const TraversalRunStats& o) {
    cycles += o.cycles;
    rays += o.rays;
    steps += o.steps;
    stepReadyCycles += o.stepReadyCycles;
    nodeReads += o.nodeReads;
    indexReads += o.indexReads;
    triangleReads += o.triangleReads;
    isectTests += o.isectTests;
    quadricTests += o.quadricTests;
    isectBusyCycles += o.isectBusyCycles;
    cycleAccurate = o.cycleAccurate;
    addPerUnit(unitRays, o.unitRays);
    addPerUnit(unitBusyCycles, o.unitBusyCycles);
    memory += o.memory;
    queues += o.queues;
    return *this;
  }
};

// The one interface over every model of a traversal unit (traversal + memory +
// intersection pipeline): golden, SystemC, Verilated RTL. `Image` is the
// memory image the unit reads (fx::GridImage, fx::OctreeImage). `traces[k]`
// answers `rays[k]`: the elements it entered in order, the tests it issued,
// its closest hit.
template <class Image>
class TraversalDevice {
 public:
  virtual ~TraversalDevice() = default;
  virtual std::string_view name() const = 0;
  // Ray slots the model was built with: the largest valid TraversalRunOptions::raysInFlight.
  virtual int maxRaysInFlight() const = 0;
  virtual TraversalRunStats run(const Image& image, std::span<const fx::QRay> rays,
                                std::vector<fx::TraversalTrace>& traces, const TraversalRunOptions& options = {}) = 0;
};

using GridDevice = TraversalDevice<fx::GridImage>;
using OctreeDevice = TraversalDevice<fx::OctreeImage>;
using BvhDevice = TraversalDevice<fx::BvhImage>;

// The golden models: each unit's walk (its descriptor's traverse()), no
// timing. Memory reads are what the hardware would issue (the descriptor's
// NodeReads), and one index and one primitive read per test.
template <class Image>
class GoldenTraversalDevice final : public TraversalDevice<Image> {
 public:
  std::string_view name() const override { return "golden"; }
  int maxRaysInFlight() const override { return 1 << 16; }
  TraversalRunStats run(const Image& image, std::span<const fx::QRay> rays, std::vector<fx::TraversalTrace>& traces,
                        const TraversalRunOptions& = {}) override {
    using Unit = fx::UnitFor<Image>;
    const typename Unit::NodeReads nodeReads(image);
    TraversalRunStats stats;
    stats.cycleAccurate = false;
    traces.clear();
    traces.reserve(rays.size());
    for (const fx::QRay& ray : rays) {
      const fx::TraversalTrace& t = traces.emplace_back(Unit::traverse(image, ray));
      stats.steps += t.visits.size();
      stats.nodeReads += nodeReads(t);
      stats.indexReads += t.tests;
      stats.triangleReads += t.tests;
      stats.isectTests += t.tests;
      stats.quadricTests += t.quadricTests;
    }
    stats.rays = rays.size();
    return stats;
  }
};

using GoldenGridDevice = GoldenTraversalDevice<fx::GridImage>;
using GoldenOctreeDevice = GoldenTraversalDevice<fx::OctreeImage>;
using GoldenBvhDevice = GoldenTraversalDevice<fx::BvhImage>;

}  // namespace lancer
