#include "driver/grid_job.h"

#include <chrono>

#include <fmt/format.h>

#include "common/error.h"
#include "driver/report.h"

namespace lancer {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string cellRun(const std::vector<uint32_t>& cells, size_t from) {
  constexpr size_t kShown = 12;
  std::string out;
  for (size_t i = from; i < cells.size() && i < from + kShown; ++i) out += fmt::format(" {}", cells[i]);
  if (cells.size() > from + kShown) out += fmt::format(" ... ({} more)", cells.size() - from - kShown);
  return out.empty() ? " (none)" : out;
}

}  // namespace

fx::GridImage buildGridImageFor(const Scene& scene, const Quantizer& quantizer, const AccelOptions& options) {
  std::vector<fx::QTriangle> triangles(scene.size());
  for (uint32_t i = 0; i < scene.size(); ++i) triangles[i] = quantizer.quantize(scene.triangles[i], i);
  const int r = options.gridResolution;
  const fx::GridRes res = r ? fx::GridRes{r, r, r} : fx::chooseGridResolution(triangles);
  return fx::buildGridImage(std::move(triangles), res);
}

std::string describeGridMismatch(const fx::QRay& ray, const fx::GridTrace& model, const fx::GridTrace& golden) {
  size_t first = 0;
  while (first < model.cells.size() && first < golden.cells.size() && model.cells[first] == golden.cells[first]) ++first;
  std::string out = fmt::format("first mismatch: ray {} (grid unit)\n", ray.id);
  out += fmt::format("  ray      {}\n", hexFields(ray));
  out += fmt::format("  cells    model {} visited, golden {}; first difference at step {}\n", model.cells.size(),
                     golden.cells.size(), first);
  out += fmt::format("    model  from step {}:{}\n", first, cellRun(model.cells, first));
  out += fmt::format("    golden from step {}:{}\n", first, cellRun(golden.cells, first));
  out += fmt::format("  tests    model {}, golden {}\n", model.tests, golden.tests);
  out += fmt::format("  model    {}\n", model.hit ? hexFields(*model.hit) : "(miss)");
  out += fmt::format("  golden   {}\n", golden.hit ? hexFields(*golden.hit) : "(miss)");
  if (model.hit && golden.hit) {
    out += fmt::format("  differing bits of isect_res_t:{}\n",
                       differingBits(fx::packWire(*model.hit), fx::packWire(*golden.hit), fx::kIsectResBits));
  }
  return out;
}

JobResult runGridJob(const fx::GridImage& image, std::span<const Ray> rays, const Quantizer& quantizer,
                     GridDevice& model, GridDevice& golden, const JobConfig& config, const ProgressFn& onProgress) {
  if (config.raysInFlight < 0 || config.raysInFlight > model.maxRaysInFlight()) {
    throw InputError(fmt::format("--rays-in-flight {}: the {} grid unit was built with {} ray slots (1..{})",
                                 config.raysInFlight, model.name(), model.maxRaysInFlight(), model.maxRaysInFlight()));
  }
  if (config.memLatency < 1 || config.memLatencyJitter < 0) {
    throw InputError(fmt::format("--mem-latency {} must be >= 1 and --mem-jitter {} >= 0", config.memLatency,
                                 config.memLatencyJitter));
  }
  JobResult job;
  job.rays.resize(rays.size());
  job.hits.resize(rays.size());
  GridRunOptions options;
  options.stream = config.stream;
  options.memLatency = config.memLatency;
  options.memLatencyJitter = config.memLatencyJitter;
  options.raysInFlight = config.raysInFlight;
  GridRunStats total;
  std::vector<fx::QRay> batch;
  std::vector<fx::GridTrace> modelTraces, goldenTraces;
  for (size_t begin = 0; begin < rays.size(); begin += config.raysPerBatch) {
    const size_t end = std::min(rays.size(), begin + config.raysPerBatch);
    batch.clear();
    for (size_t i = begin; i < end; ++i) {
      job.rays[i] = quantizer.quantize(rays[i], uint32_t(i));
      if (job.rays[i]) batch.push_back(job.rays[i]->q);
    }
    auto start = std::chrono::steady_clock::now();
    const GridRunStats stats = model.run(image, batch, modelTraces, options);
    job.modelSeconds += secondsSince(start);
    start = std::chrono::steady_clock::now();
    golden.run(image, batch, goldenTraces, {});
    job.goldenSeconds += secondsSince(start);
    total.cycles += stats.cycles;
    total.voxelSteps += stats.voxelSteps;
    total.cellReads += stats.cellReads;
    total.indexReads += stats.indexReads;
    total.triangleReads += stats.triangleReads;
    total.isectTests += stats.isectTests;
    total.isectBusyCycles += stats.isectBusyCycles;
    job.cycleAccurate = stats.cycleAccurate;
    for (size_t k = 0; k < batch.size(); ++k) {
      const uint32_t id = batch[k].id;
      const fx::GridTrace* mine = k < modelTraces.size() ? &modelTraces[k] : nullptr;
      if (mine) job.hits[id] = mine->hit;
      if (mine && *mine == goldenTraces[k]) continue;
      ++job.mismatchedRays;
      if (!job.firstMismatch) {
        job.firstMismatch = MismatchReport{id, describeGridMismatch(batch[k], mine ? *mine : fx::GridTrace{}, goldenTraces[k])};
      }
    }
    if (onProgress) onProgress(end - begin);
  }
  job.cycles = total.cycles;
  job.intersectionTests = total.isectTests;
  const double cycles = double(std::max<uint64_t>(total.cycles, 1));
  job.addCounter("grid_resolution_x", "grid cells x", image.res[0]);
  job.addCounter("grid_resolution_y", "grid cells y", image.res[1]);
  job.addCounter("grid_resolution_z", "grid cells z", image.res[2]);
  job.addCounter("voxel_steps", "voxel steps", double(total.voxelSteps));
  job.addCounter("memory_reads", "memory reads", double(total.memoryReads()));
  job.addCounter("cell_reads", "cell table reads", double(total.cellReads));
  job.addCounter("index_reads", "index list reads", double(total.indexReads));
  job.addCounter("triangle_reads", "triangle reads", double(total.triangleReads));
  if (job.cycleAccurate) {  // timing figures mean nothing for the golden model
    job.addCounter("steps_per_cycle", "voxel steps/cycle", double(total.voxelSteps) / cycles);
    job.addCounter("isect_utilization", "isect busy fraction", double(total.isectBusyCycles) / cycles);
    job.addCounter("mem_latency", "memory latency", config.memLatency);
    job.addCounter("rays_in_flight", "rays in flight",
                   config.raysInFlight ? config.raysInFlight : model.maxRaysInFlight());
  }
  return job;
}

}  // namespace lancer
