#pragma once

// A hardware job: rays through one hardware path (--accel) on one model
// (--model), compared bit for bit with the golden model. The CLI and the
// reports see only this; each path (the host BVH feeding the intersection
// pipeline, the grid unit, ...) fills it in its own way.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "driver/chip.h"
#include "driver/isect_device.h"
#include "driver/quantize.h"
#include "golden/unit.h"
#include "ref/accel.h"

namespace lancer {

// The first ray on which the model and the golden model disagree: a
// multi-line reproducer (inputs in hex, both outputs, the differing bits).
struct MismatchReport {
  uint32_t rayId = 0;
  std::string details;
};

// A unit-specific figure for the summary and the JSON report.
struct JobCounter {
  std::string key;    // JSON key, e.g. "voxel_steps"
  std::string label;  // summary label, e.g. "voxel steps"
  double value = 0;
};

struct JobResult {
  std::vector<std::optional<QuantizedRay>> rays;     // per ray; nullopt: missed the lattice cube
  std::vector<std::optional<fx::IsectResult>> hits;  // the model's closest hit per ray
  uint64_t mismatchedRays = 0;
  std::optional<MismatchReport> firstMismatch;
  uint64_t cycles = 0;
  bool cycleAccurate = true;
  uint64_t intersectionTests = 0;
  uint64_t quadricTests = 0;  // of which ray-quadric (the isect path on a scene with quadrics)
  uint64_t steps = 0;        // traversal units: cells or nodes entered (0 on the isect path)
  uint64_t memoryReads = 0;  // traversal units: reads of every region
  uint64_t nodeBytes = 0;    // traversal units: bytes of the node-port reads (cells, child groups, nodes)
  std::vector<JobCounter> counters;
  double modelSeconds = 0;   // host time inside the model
  double goldenSeconds = 0;  // host time inside the golden model
  std::optional<ChipFigures> chip;  // traversal units on a cycle-accurate model
  // Primitive ids from here on are quadrics (the scene's triangle count), whose
  // results say the side in u_num (0 entering, 1 leaving) rather than a
  // barycentric; no quadrics: the largest id.
  uint32_t firstQuadric = UINT32_MAX;

  void addCounter(std::string key, std::string label, double value) {
    counters.push_back({std::move(key), std::move(label), value});
  }
};

struct JobConfig {
  std::string model = "golden";
  StreamOptions stream;
  AccelOptions accel;        // --grid-res, --octree-depth, ...
  int memLatency = 20;       // traversal units: memory latency in cycles
  int memLatencyJitter = 0;  // and its random extra per request
  int raysInFlight = 0;      // ray slots; 0 = all the unit was built with
  // The chip (docs/chip.md): traversal units sharing a memory system. Its
  // clockMhz is the run's; the fixed model's latency is memLatency's.
  int units = 1;
  int dispatchBatch = 32;
  Schedule schedule = Schedule::Fifo;  // the order the dispatcher hands rays out (driver/schedule.h)
  mem::RayQueueConfig queues;          // the treelet schedule's ray queues
  int hostThreads = 1;
  mem::MemoryConfig memory;
  // Rays per model run, per unit: a chip of N units runs N times as many at
  // once. (The memory hierarchy outlives the runs: driver/job.cpp.)
  size_t raysPerBatch = 4096;
  // The isect path: narrow widths at which to model a dual-precision front end
  // (golden/dual.h), reported as the share of tests escalated to full width.
  std::vector<int> dualNarrowBits;
};

using ProgressFn = std::function<void(size_t raysDone)>;

// The hardware paths of --accel (fx::UnitKind): the host's BVH feeding the
// intersection pipeline ("isect"), then every traversal unit by its descriptor's
// name ("grid", "octree").
std::vector<fx::UnitKind> hardwarePaths();
std::vector<std::string> hardwarePathNames();
std::string_view toString(fx::UnitKind path);
// Throws InputError naming the paths for an unknown name.
fx::UnitKind parseHardwarePath(std::string_view name);
// The models a path has ("golden", "systemc", "rtl", ...).
std::vector<std::string> modelsFor(fx::UnitKind path);

// Rays as a job takes them: ray k quantized with id k, nullopt where it misses
// the lattice cube.
using QuantizedRays = std::vector<std::optional<QuantizedRay>>;
QuantizedRays quantizeRays(const Quantizer& quantizer, std::span<const Ray> rays);

// A hardware path (--accel) on a model (--model), set up once for a scene: its
// memory image or host BVH, the model and the golden model. Each run() is one
// job: `rays` (ray k has id k) through both, compared ray by ray bit for bit.
// A path runs any number of jobs (the waves of an effects run).
class HardwarePath {
 public:
  virtual ~HardwarePath() = default;
  virtual JobResult run(std::span<const std::optional<QuantizedRay>> rays, const ProgressFn& onProgress = {}) = 0;
  // The figures of the structure the path built for the scene (a traversal
  // unit's memory image: the grid's resolution, the octree's depth and nodes,
  // the BVH's); none for the pipeline fed by the host.
  virtual std::vector<JobCounter> structure() const { return {}; }
};

// Throws InputError for an unknown model, or a configuration the model cannot run.
std::unique_ptr<HardwarePath> makeHardwarePath(fx::UnitKind path, const Scene& scene, const Quantizer& quantizer,
                                               const JobConfig& config);

// Runs `rays` through the path: quantizeRays, then one job.
JobResult runJob(fx::UnitKind path, const Scene& scene, std::span<const Ray> rays,
                 const Quantizer& quantizer, const JobConfig& config, const ProgressFn& onProgress = {});

}  // namespace lancer
