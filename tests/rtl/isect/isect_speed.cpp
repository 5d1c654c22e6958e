// Host speed of the intersection models on a saturated stream: pairs per
// second (wall clock and process CPU time) for the Verilated RTL and the golden
// model, pairs packed and unpacked included, stimulus generation excluded.
// Usage: rtl_isect_speed [PAIRS]   (default 1000000)
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "driver/golden_device.h"
#include "driver/verilator_isect_device.h"
#include "isect/isect_cases.h"

int main(int argc, char** argv) {
  using namespace lancer;
  const size_t count = argc > 1 ? size_t(std::stoull(argv[1])) : 1000000;
  const auto pairs = rtltest::randomPairs(count, 2024);
  auto measure = [&](IsectDevice& device, const std::vector<IsectRequest>& pairs) {
    const size_t count = pairs.size();
    std::vector<fx::IsectResult> results;
    results.reserve(count);
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpuStart = std::clock();
    const StreamStats stats = device.run(pairs, results);
    const double cpu = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%-7s %9zu pairs  wall %7.3f s %7.3f M tests/s  cpu %7.3f s %7.3f M tests/s  %9llu cycles\n",
                std::string(device.name()).c_str(), count, wall, double(count) / wall / 1e6, cpu,
                double(count) / cpu / 1e6, static_cast<unsigned long long>(stats.cycles));
    return results;
  };
  VerilatorIsectDevice rtl;
  GoldenIsectDevice golden;
  std::printf("saturated stream of distinct random pairs:\n");
  const auto rtlRandom = measure(rtl, pairs);
  if (rtlRandom != measure(golden, pairs)) {
    std::printf("MISMATCH between rtl and golden\n");
    return 1;
  }
  // Each ray against 8 triangles, as a candidate list streams: the ray is
  // packed once per 8 pairs.
  const auto mesh = rtltest::watertightRays(count / rtltest::kOctahedronFaces, 2025);
  std::printf("saturated stream, one ray against 8 triangles:\n");
  const auto rtlMesh = measure(rtl, mesh);
  if (rtlMesh != measure(golden, mesh)) {
    std::printf("MISMATCH between rtl and golden\n");
    return 1;
  }
  // Throughput under backpressure (clock cycles, deterministic).
  const std::vector<IsectRequest> some(pairs.begin(), pairs.begin() + std::min<size_t>(count, 100000));
  std::printf("results per cycle under backpressure (%zu pairs):\n", some.size());
  for (const auto& [stall, idle] : {std::pair{0.0, 0.0}, {0.1, 0.0}, {0.3, 0.0}, {0.0, 0.3}, {0.3, 0.2}, {0.5, 0.5}}) {
    std::vector<fx::IsectResult> results;
    StreamOptions options;
    options.outputStallProbability = stall;
    options.inputIdleProbability = idle;
    const StreamStats stats = rtl.run(some, results, options);
    std::printf("  stall %.1f idle %.1f: %.4f results/cycle (%llu cycles, %llu input stalls)\n", stall, idle,
                double(stats.results) / double(stats.cycles),
                static_cast<unsigned long long>(stats.cycles),
                static_cast<unsigned long long>(stats.inputStalls));
  }
  return 0;
}
