#include "driver/traversal_job.h"

#include <chrono>

#include <fmt/format.h>

#include "common/error.h"
#include "driver/report.h"

namespace lancer {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string visitRun(const std::vector<uint32_t>& visits, size_t from) {
  constexpr size_t kShown = 12;
  std::string out;
  for (size_t i = from; i < visits.size() && i < from + kShown; ++i) out += fmt::format(" {}", visits[i]);
  if (visits.size() > from + kShown) out += fmt::format(" ... ({} more)", visits.size() - from - kShown);
  return out.empty() ? " (none)" : out;
}

// What differs between the units in their job: names and image counters.
template <class Image>
struct TraversalUnit;

template <>
struct TraversalUnit<fx::GridImage> {
  static constexpr const char* kName = "grid";
  static constexpr const char* kElement = "cells";
  static constexpr const char* kStepsKey = "voxel_steps";
  static constexpr const char* kStepsLabel = "voxel steps";
  static constexpr const char* kReadsKey = "cell_reads";
  static constexpr const char* kReadsLabel = "cell table reads";
  static void addImageCounters(JobResult& job, const fx::GridImage& image) {
    job.addCounter("grid_resolution_x", "grid cells x", image.res[0]);
    job.addCounter("grid_resolution_y", "grid cells y", image.res[1]);
    job.addCounter("grid_resolution_z", "grid cells z", image.res[2]);
  }
};

template <>
struct TraversalUnit<fx::OctreeImage> {
  static constexpr const char* kName = "octree";
  static constexpr const char* kElement = "nodes";
  static constexpr const char* kStepsKey = "node_steps";
  static constexpr const char* kStepsLabel = "node steps";
  static constexpr const char* kReadsKey = "node_reads";
  static constexpr const char* kReadsLabel = "child group reads";
  static void addImageCounters(JobResult& job, const fx::OctreeImage& image) {
    job.addCounter("octree_depth", "octree depth", image.depth);
    job.addCounter("octree_max_depth", "octree max depth", image.maxDepth);
    job.addCounter("octree_leaf_size", "octree leaf size", image.leafSize);
    job.addCounter("octree_nodes", "octree nodes", double(image.nodes.size()));
  }
};

void accumulate(TraversalRunStats& total, const TraversalRunStats& stats) {
  total.cycles += stats.cycles;
  total.rays += stats.rays;
  total.steps += stats.steps;
  total.stepReadyCycles += stats.stepReadyCycles;
  total.nodeReads += stats.nodeReads;
  total.indexReads += stats.indexReads;
  total.triangleReads += stats.triangleReads;
  total.isectTests += stats.isectTests;
  total.isectBusyCycles += stats.isectBusyCycles;
  total.cycleAccurate = stats.cycleAccurate;
}

}  // namespace

fx::GridImage buildGridImageFor(const Scene& scene, const Quantizer& quantizer, const AccelOptions& options) {
  std::vector<fx::QTriangle> triangles = quantizer.quantize(scene);
  const int r = options.gridResolution;
  const fx::GridRes res = r ? fx::GridRes{r, r, r} : fx::chooseGridResolution(triangles);
  return fx::buildGridImage(std::move(triangles), res);
}

fx::OctreeImage buildOctreeImageFor(const Scene& scene, const Quantizer& quantizer, const AccelOptions& options) {
  std::vector<fx::QTriangle> triangles = quantizer.quantize(scene);
  const int depth = options.octreeMaxDepth ? options.octreeMaxDepth : fx::defaultOctreeDepth(triangles.size());
  const int leaf = options.octreeLeafSize ? options.octreeLeafSize : fx::kDefaultOctreeLeafSize;
  return fx::buildOctreeImage(std::move(triangles), depth, leaf);
}

std::string describeTraversalMismatch(std::string_view unit, std::string_view element, const fx::QRay& ray,
                                      const fx::TraversalTrace& model, const fx::TraversalTrace& golden) {
  size_t first = 0;
  while (first < model.visits.size() && first < golden.visits.size() && model.visits[first] == golden.visits[first]) {
    ++first;
  }
  std::string out = fmt::format("first mismatch: ray {} ({} unit)\n", ray.id, unit);
  out += fmt::format("  ray      {}\n", hexFields(ray));
  out += fmt::format("  {:<8} model {} visited, golden {}; first difference at step {}\n", element,
                     model.visits.size(), golden.visits.size(), first);
  out += fmt::format("    model  from step {}:{}\n", first, visitRun(model.visits, first));
  out += fmt::format("    golden from step {}:{}\n", first, visitRun(golden.visits, first));
  out += fmt::format("  tests    model {}, golden {}\n", model.tests, golden.tests);
  out += fmt::format("  model    {}\n", model.hit ? hexFields(*model.hit) : "(miss)");
  out += fmt::format("  golden   {}\n", golden.hit ? hexFields(*golden.hit) : "(miss)");
  if (model.hit && golden.hit) {
    out += fmt::format("  differing bits of isect_res_t:{}\n",
                       differingBits(fx::packWire(*model.hit), fx::packWire(*golden.hit), fx::kIsectResBits));
  }
  return out;
}

template <class Image>
JobResult runTraversalJob(const Image& image, std::span<const std::optional<QuantizedRay>> rays,
                          TraversalDevice<Image>& model, TraversalDevice<Image>& golden, const JobConfig& config,
                          const ProgressFn& onProgress) {
  using Unit = TraversalUnit<Image>;
  if (config.raysInFlight < 0 || config.raysInFlight > model.maxRaysInFlight()) {
    throw InputError(fmt::format("--rays-in-flight {}: the {} {} unit was built with {} ray slots (1..{})",
                                 config.raysInFlight, model.name(), Unit::kName, model.maxRaysInFlight(),
                                 model.maxRaysInFlight()));
  }
  if (config.memLatency < 1 || config.memLatencyJitter < 0) {
    throw InputError(fmt::format("--mem-latency {} must be >= 1 and --mem-jitter {} >= 0", config.memLatency,
                                 config.memLatencyJitter));
  }
  JobResult job;
  job.rays.resize(rays.size());
  job.hits.resize(rays.size());
  TraversalRunOptions options;
  options.stream = config.stream;
  options.memLatency = config.memLatency;
  options.memLatencyJitter = config.memLatencyJitter;
  options.raysInFlight = config.raysInFlight;
  TraversalRunStats total;
  std::vector<fx::QRay> batch;
  std::vector<fx::TraversalTrace> modelTraces, goldenTraces;
  for (size_t begin = 0; begin < rays.size(); begin += config.raysPerBatch) {
    const size_t end = std::min(rays.size(), begin + config.raysPerBatch);
    batch.clear();
    for (size_t i = begin; i < end; ++i) {
      job.rays[i] = rays[i];
      if (!job.rays[i]) continue;
      job.rays[i]->q.id = uint32_t(i);
      batch.push_back(job.rays[i]->q);
    }
    auto start = std::chrono::steady_clock::now();
    accumulate(total, model.run(image, batch, modelTraces, options));
    job.modelSeconds += secondsSince(start);
    start = std::chrono::steady_clock::now();
    golden.run(image, batch, goldenTraces, {});
    job.goldenSeconds += secondsSince(start);
    for (size_t k = 0; k < batch.size(); ++k) {
      const uint32_t id = batch[k].id;
      const fx::TraversalTrace* mine = k < modelTraces.size() ? &modelTraces[k] : nullptr;
      if (mine) job.hits[id] = mine->hit;
      if (mine && *mine == goldenTraces[k]) continue;
      ++job.mismatchedRays;
      if (!job.firstMismatch) {
        job.firstMismatch = MismatchReport{
            id, describeTraversalMismatch(Unit::kName, Unit::kElement, batch[k], mine ? *mine : fx::TraversalTrace{},
                                          goldenTraces[k])};
      }
    }
    if (onProgress) onProgress(end - begin);
  }
  job.cycles = total.cycles;
  job.cycleAccurate = total.cycleAccurate;
  job.intersectionTests = total.isectTests;
  job.steps = total.steps;
  job.memoryReads = total.memoryReads();
  const double cycles = double(std::max<uint64_t>(total.cycles, 1));
  Unit::addImageCounters(job, image);
  job.addCounter(Unit::kStepsKey, Unit::kStepsLabel, double(total.steps));
  job.addCounter("memory_reads", "memory reads", double(total.memoryReads()));
  job.addCounter(Unit::kReadsKey, Unit::kReadsLabel, double(total.nodeReads));
  job.addCounter("index_reads", "index list reads", double(total.indexReads));
  job.addCounter("triangle_reads", "triangle reads", double(total.triangleReads));
  if (job.cycleAccurate) {  // timing figures mean nothing for the golden model
    job.addCounter("steps_per_cycle", fmt::format("{}/cycle", Unit::kStepsLabel), double(total.steps) / cycles);
    if (total.stepReadyCycles) {
      job.addCounter("steps_per_ready_cycle", "steps/ready cycle",
                     double(total.steps) / double(total.stepReadyCycles));
    }
    job.addCounter("isect_utilization", "isect busy fraction", double(total.isectBusyCycles) / cycles);
    job.addCounter("mem_latency", "memory latency", config.memLatency);
    job.addCounter("rays_in_flight", "rays in flight",
                   config.raysInFlight ? config.raysInFlight : model.maxRaysInFlight());
  }
  return job;
}

template JobResult runTraversalJob(const fx::GridImage&, std::span<const std::optional<QuantizedRay>>, GridDevice&,
                                   GridDevice&, const JobConfig&, const ProgressFn&);
template JobResult runTraversalJob(const fx::OctreeImage&, std::span<const std::optional<QuantizedRay>>,
                                   OctreeDevice&, OctreeDevice&, const JobConfig&, const ProgressFn&);

}  // namespace lancer
