#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "golden/quadric.h"
#include "golden/records.h"

namespace lancer {

// One ray-triangle pair as it enters the intersection pipeline.
struct IsectRequest {
  fx::QRay ray;
  fx::QTriangle tri;
};

// One ray-quadric pair as it enters the quadric pipeline (rt_quadric).
struct QuadricRequest {
  fx::QRay ray;
  fx::QQuadric quadric;
};

// How a run is driven; every device honours what applies to it.
struct StreamOptions {
  double outputStallProbability = 0.0;  // chance per cycle that the consumer is not ready
  double inputIdleProbability = 0.0;    // chance per cycle that the producer holds back
  uint64_t seed = 1;                    // for both of the above
  std::string wavePath;                 // FST waveform (RTL models only); empty = off
};

// What the hardware did, counted in clock cycles of the simulated unit.
struct StreamStats {
  uint64_t cycles = 0;        // from the first request offered to the last result taken
  uint64_t requests = 0;      // pairs accepted
  uint64_t results = 0;       // results delivered
  uint64_t inputStalls = 0;   // cycles a request was offered but not accepted
  bool cycleAccurate = true;  // false for the golden model, whose cycles are the ideal count
};

// The one interface over every model of the intersection pipelines: golden
// (bit-accurate, ideal timing), SystemC cycle model, Verilated RTL in C++ and
// Verilated RTL in SystemC. The driver, the comparison and the CLI use only this.
// A device holds both pipelines: rt_isect (ray-triangle pairs, run) and
// rt_quadric beside it (ray-quadric pairs, runQuadrics).
class IsectDevice {
 public:
  virtual ~IsectDevice() = default;
  virtual std::string_view name() const = 0;
  // Streams `requests` into the unit in order through valid/ready and collects
  // every result in the order the unit delivers it. May be called repeatedly.
  virtual StreamStats run(std::span<const IsectRequest> requests,
                          std::vector<fx::IsectResult>& results,
                          const StreamOptions& options = {}) = 0;
  // The same through the quadric pipeline (rt_quadric). A model that has no
  // quadric pipeline throws InputError naming itself.
  virtual StreamStats runQuadrics(std::span<const QuadricRequest> requests,
                                  std::vector<fx::IsectResult>& results,
                                  const StreamOptions& options = {}) = 0;
};

}  // namespace lancer
