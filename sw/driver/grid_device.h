#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "driver/isect_device.h"
#include "golden/grid.h"

namespace lancer {

// How a run of the grid unit is driven.
struct GridRunOptions {
  StreamOptions stream;      // ray input bubbles, result/visit output stalls, seed, waveform
  int memLatency = 20;       // cycles from a memory request to its response (>= 1)
  int memLatencyJitter = 0;  // extra 0..jitter cycles per request, random (seeded); responses stay in order per port
  int raysInFlight = 0;      // ray slots to use; 0 = all the unit was built with
};

// What the unit did, in clock cycles of the simulated chip.
struct GridRunStats {
  uint64_t cycles = 0;          // first ray offered to last result taken
  uint64_t rays = 0;
  uint64_t voxelSteps = 0;      // cells entered, summed over rays
  uint64_t cellReads = 0;       // memory reads per region
  uint64_t indexReads = 0;
  uint64_t triangleReads = 0;
  uint64_t isectTests = 0;      // pairs the intersection pipeline accepted
  uint64_t isectBusyCycles = 0; // cycles in which it accepted one
  bool cycleAccurate = true;    // false for the golden model (no timing)

  uint64_t memoryReads() const { return cellReads + indexReads + triangleReads; }
};

// The one interface over every model of the grid unit (traversal + memory +
// intersection pipeline): golden, SystemC, Verilated RTL. `traces[k]` answers
// `rays[k]`: the cells it visited in order, the tests it issued, its closest hit.
class GridDevice {
 public:
  virtual ~GridDevice() = default;
  virtual std::string_view name() const = 0;
  // Ray slots the model was built with: the largest valid GridRunOptions::raysInFlight.
  virtual int maxRaysInFlight() const = 0;
  virtual GridRunStats run(const fx::GridImage& image, std::span<const fx::QRay> rays,
                           std::vector<fx::GridTrace>& traces, const GridRunOptions& options = {}) = 0;
};

// The golden model: the traversal of sw/golden/grid.h, no timing.
class GoldenGridDevice final : public GridDevice {
 public:
  std::string_view name() const override { return "golden"; }
  int maxRaysInFlight() const override { return 1 << 16; }
  GridRunStats run(const fx::GridImage& image, std::span<const fx::QRay> rays, std::vector<fx::GridTrace>& traces,
                   const GridRunOptions& options = {}) override;
};

}  // namespace lancer
