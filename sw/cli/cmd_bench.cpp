// lancer bench: single-thread throughput of the reference structures and Embree
// on the same primary rays, measured side by side in one run (medians).
#include <fmt/format.h>

#include "cli/options.h"
#include "common/progress.h"
#include "oracle/make_accel.h"
#include "ref/benchmark.h"

namespace lancer::cli {

void addBenchCommand(CLI::App& app) {
  struct Args {
    SceneOptions scene;
    CameraArgs camera;
    AccelOptions options;
    int repetitions = 5;
    std::string report;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("bench", "Mrays/s of grid, octree, BVH and Embree on the same rays");
  args->scene.add(*cmd);
  args->camera.add(*cmd);
  cmd->add_option("--repetitions", args->repetitions, "Timed passes per structure (median reported)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--grid-res", args->options.gridResolution, "Grid voxels along the longest axis");
  cmd->add_option("--octree-depth", args->options.octreeMaxDepth, "Octree maximum depth");
  cmd->add_option("--octree-leaf", args->options.octreeLeafSize, "Octree leaf size");
  cmd->add_option("--report", args->report, "JSON report file");
  cmd->callback([args] {
    const Scene scene = args->scene.load();
    const std::vector<Ray> rays = frameScene(scene, args->camera.resolve()).generateRays();
    std::vector<BenchCandidate> candidates;
    for (AccelKind kind : {AccelKind::Grid, AccelKind::Octree, AccelKind::Bvh, AccelKind::Embree}) {
      candidates.push_back({std::string(toString(kind)), [&scene, kind, args] {
                              return makeAccel(kind, scene, args->options);
                            }});
    }
    BenchOptions options;
    options.repetitions = args->repetitions;
    Progress progress("bench", uint64_t(args->repetitions) * candidates.size());
    options.progress = [&](const std::string&, int, int, int) { progress.advance(); };
    const BenchReport bench = runBenchmark(scene, rays, candidates, options);
    progress.finish();

    fmt::print("bench: {} ({} triangles), {} primary rays, {} repetitions, one thread\n", scene.name,
               bench.triangles, bench.rays, bench.repetitions);
    fmt::print("  {:<8} {:>10} {:>10} {:>10} {:>10} {:>9} {:>10} {:>10}\n", "accel", "Mrays/s", "min", "max",
               "cpu Mr/s", "build s", "hits", "agree");
    nlohmann::json report = {{"command", "bench"},
                             {"scene", scene.name},
                             {"scene_numbers", toString(scene.numbers)},
                             {"triangles", bench.triangles},
                             {"rays", bench.rays},
                             {"repetitions", bench.repetitions},
                             {"threads", 1}};
    for (const BenchResult& r : bench.results) {
      fmt::print("  {:<8} {:>10.3f} {:>10.3f} {:>10.3f} {:>10.3f} {:>9.3f} {:>10} {:>9.3f}%\n", r.name,
                 r.medianMraysPerSecond, r.minMraysPerSecond, r.maxMraysPerSecond, r.medianCpuMraysPerSecond,
                 r.buildSeconds.value_or(0.0),
                 r.hits, 100.0 * double(r.agreeing) / double(std::max<size_t>(1, bench.rays)));
      report[r.name + "_mrays_per_s"] = r.medianMraysPerSecond;
      report[r.name + "_cpu_mrays_per_s"] = r.medianCpuMraysPerSecond;
      report[r.name] = {{"median_mrays_per_s", r.medianMraysPerSecond},
                        {"median_cpu_mrays_per_s", r.medianCpuMraysPerSecond},
                        {"samples_mrays_per_s", r.mraysPerSecond},
                        {"build_seconds", r.buildSeconds.value_or(0.0)},
                        {"hits", r.hits},
                        {"agreeing_with_first", r.agreeing},
                        {"identical_to_first", r.identical}};
    }
    const auto& results = bench.results;
    if (results.size() == 4 && results[3].medianMraysPerSecond > 0) {
      const double ratio = results[2].medianMraysPerSecond / results[3].medianMraysPerSecond;
      const double cpuRatio = results[3].medianCpuMraysPerSecond > 0
                                  ? results[2].medianCpuMraysPerSecond / results[3].medianCpuMraysPerSecond
                                  : 0.0;
      fmt::print("  bvh / embree = {:.2f} (wall clock), {:.2f} (thread CPU clock)\n", ratio, cpuRatio);
      report["bvh_over_embree_cpu"] = cpuRatio;
      report["bvh_over_embree"] = ratio;
    }
    writeReport(args->report, report);
  });
}

}  // namespace lancer::cli
