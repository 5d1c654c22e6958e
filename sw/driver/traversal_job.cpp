#include "driver/traversal_job.h"

#include <chrono>
#include <tuple>

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

}  // namespace

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
  out += fmt::format("  tests    model {} ({} of quadrics), golden {} ({})\n", model.tests, model.quadricTests,
                     golden.tests, golden.quadricTests);
  out += fmt::format("  model    {}\n", model.hit ? hexFields(*model.hit) : "(miss)");
  out += fmt::format("  golden   {}\n", golden.hit ? hexFields(*golden.hit) : "(miss)");
  if (model.hit && golden.hit) {
    out += fmt::format("  differing bits of isect_res_t:{}\n",
                       differingBits(fx::packWire(*model.hit), fx::packWire(*golden.hit), fx::kIsectResBits));
  }
  return out;
}

TraversalRunOptions traversalOptionsOf(const JobConfig& config) {
  TraversalRunOptions options;
  options.stream = config.stream;
  options.memLatency = config.memLatency;
  options.memLatencyJitter = config.memLatencyJitter;
  options.raysInFlight = config.raysInFlight;
  options.units = config.units;
  options.dispatchBatch = config.dispatchBatch;
  options.hostThreads = config.hostThreads;
  options.memory = config.memory;
  options.treelets = config.schedule == Schedule::Treelet;
  options.queues = config.queues;
  return options;
}

template <class Image>
JobResult runTraversalJob(const Image& image, std::span<const std::optional<QuantizedRay>> rays,
                          TraversalDevice<Image>& model, TraversalDevice<Image>& golden, const JobConfig& config,
                          const ProgressFn& onProgress, mem::MemorySystem* sharedMemory) {
  using Unit = fx::UnitFor<Image>;
  if (config.raysInFlight < 0 || config.raysInFlight > model.maxRaysInFlight()) {
    throw InputError(fmt::format("--rays-in-flight {}: the {} {} unit was built with {} ray slots (1..{})",
                                 config.raysInFlight, model.name(), Unit::kNames.unit, model.maxRaysInFlight(),
                                 model.maxRaysInFlight()));
  }
  if (config.memLatency < 1 || config.memLatencyJitter < 0) {
    throw InputError(fmt::format("--mem-latency {} must be >= 1 and --mem-jitter {} >= 0", config.memLatency,
                                 config.memLatencyJitter));
  }
  if (config.schedule == Schedule::Treelet) {
    if constexpr (!fx::SuspendsWalks<Unit>) {
      throw InputError(fmt::format("--schedule treelet: the {} unit cannot set walks aside; the treelet schedule "
                                   "runs on the BVH and octree units (--accel bvh|octree)",
                                   Unit::kNames.unit));
    } else if (!fx::hasTreeletLayout(image)) {
      throw InputError(fmt::format("--schedule treelet needs a treelet layout: {} N (the on-chip budget of a "
                                   "treelet, e.g. 32768; docs/scheduling.md)",
                                   Unit::kTreeletFlag));
    }
  }
  JobResult job;
  job.rays.assign(rays.begin(), rays.end());
  job.hits.resize(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    if (job.rays[i]) job.rays[i]->q.id = uint32_t(i);
  }
  TraversalRunOptions options = traversalOptionsOf(config);
  checkChipOptions(options);
  options.sharedMemory = sharedMemory;
  // The schedule's order of the whole job; the batches are its runs.
  auto start = std::chrono::steady_clock::now();
  const std::vector<uint32_t> order = dispatchOrder(config.schedule, job.rays);
  SortCost sort;
  if (sortsRays(config.schedule)) {
    sort = chipSortCost(order.size(), memoryConfigOf(options));
    sort.hostSeconds = secondsSince(start);
  }
  if (onProgress && order.size() < rays.size()) onProgress(rays.size() - order.size());  // outside the lattice
  TraversalRunStats total;
  fx::TreeletCrossings treelets;
  std::vector<fx::QRay> batch;
  std::vector<fx::TraversalTrace> modelTraces, goldenTraces;
  const size_t raysPerBatch = config.raysPerBatch * size_t(config.units);
  for (size_t begin = 0; begin < order.size(); begin += raysPerBatch) {
    const size_t end = std::min(order.size(), begin + raysPerBatch);
    batch.clear();
    for (size_t k = begin; k < end; ++k) batch.push_back(job.rays[order[k]]->q);
    start = std::chrono::steady_clock::now();
    total += model.run(image, batch, modelTraces, options);
    job.modelSeconds += secondsSince(start);
    start = std::chrono::steady_clock::now();
    golden.run(image, batch, goldenTraces, {});
    if constexpr (fx::SuspendsWalks<Unit>) {
      for (const fx::QRay& ray : batch) treelets += Unit::treeletCrossings(image, ray);
    }
    job.goldenSeconds += secondsSince(start);
    for (size_t k = 0; k < batch.size(); ++k) {
      const uint32_t id = batch[k].id;
      const fx::TraversalTrace* mine = k < modelTraces.size() ? &modelTraces[k] : nullptr;
      if (mine) job.hits[id] = mine->hit;
      if (mine && *mine == goldenTraces[k]) continue;
      ++job.mismatchedRays;
      if (!job.firstMismatch) {
        job.firstMismatch = MismatchReport{
            id, describeTraversalMismatch(Unit::kNames.unit, Unit::kNames.elements, batch[k], mine ? *mine : fx::TraversalTrace{},
                                          goldenTraces[k])};
      }
    }
    if (onProgress) onProgress(end - begin);
  }
  job.cycles = total.cycles;
  job.cycleAccurate = total.cycleAccurate;
  job.intersectionTests = total.isectTests;
  job.quadricTests = total.quadricTests;
  // Quadrics' ids follow the triangles' (the scene's one id space).
  if (!image.quadrics.empty()) job.firstQuadric = uint32_t(image.triangles.size());
  job.steps = total.steps;
  job.memoryReads = total.memoryReads();
  job.nodeBytes = total.nodeReads * nodeReadBytes<Unit>();
  const double cycles = double(std::max<uint64_t>(total.cycles, 1));
  job.counters = imageFigures<Unit>(image);
  job.addCounter(Unit::kNames.stepsKey, Unit::kNames.stepsLabel, double(total.steps));
  job.addCounter("memory_reads", "memory reads", double(total.memoryReads()));
  job.addCounter(Unit::kNames.readsKey, Unit::kNames.readsLabel, double(total.nodeReads));
  job.addCounter("node_bytes", fmt::format("{} bytes", Unit::kNames.nodeTable), double(job.nodeBytes));
  job.addCounter("index_reads", "index list reads", double(total.indexReads));
  job.addCounter("triangle_reads", "triangle reads", double(total.triangleReads));
  if (!image.quadrics.empty()) job.addCounter("quadric_tests", "ray-quadric tests", double(total.quadricTests));
  if (job.cycleAccurate) {  // timing figures mean nothing for the golden model
    job.addCounter("steps_per_cycle", fmt::format("{}/cycle", Unit::kNames.stepsLabel), double(total.steps) / cycles);
    if (total.stepReadyCycles) {
      job.addCounter("steps_per_ready_cycle", "steps/ready cycle",
                     double(total.steps) / double(total.stepReadyCycles));
    }
    job.addCounter("isect_utilization", "isect busy fraction", double(total.isectBusyCycles) / cycles);
    job.addCounter("mem_latency", "memory latency", config.memLatency);
    job.addCounter("rays_in_flight", "rays in flight",
                   config.raysInFlight ? config.raysInFlight : model.maxRaysInFlight());
    if (!total.unitRays.empty()) {
      job.chip = ChipFigures{memoryConfigOf(options), total.unitRays, total.unitBusyCycles, total.memory,
                             config.schedule, sort, treelets, total.quadricTests, config.queues, total.queues};
    }
  }
  return job;
}

// runTraversalJob for every unit: the explicit instantiation of all() emits
// each one.
template <class Units>
struct TraversalJobs;
template <class... Units>
struct TraversalJobs<std::tuple<Units...>> {
  static auto all() { return std::tuple{&runTraversalJob<typename Units::Image>...}; }
};
template struct TraversalJobs<fx::TraversalUnits>;

}  // namespace lancer
