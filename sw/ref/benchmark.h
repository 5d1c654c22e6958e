#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ref/accel.h"

namespace lancer {

// The library behind `lancer bench`: single-thread closest-hit throughput of
// several structures over the same rays, measured side by side in one run. No
// option parsing and no printing; the CLI formats the returned report.

// A structure already built by the caller (build time unknown unless given).
struct BenchSubject {
  std::string name;  // report key, e.g. "bvh"; the CLI writes "<name>_mrays_per_s"
  const Accel* accel = nullptr;
  std::optional<double> buildSeconds;
};

// A structure the benchmark builds itself, so it can time the build.
struct BenchCandidate {
  std::string name;
  std::function<std::unique_ptr<Accel>()> build;
};

// Called after every timed pass: the structure just measured, the repetition
// (0-based), and how many of all passes are done.
using BenchProgressFn =
    std::function<void(const std::string& name, int repetition, int donePasses, int totalPasses)>;

struct BenchOptions {
  int repetitions = 5;  // timed passes per structure, interleaved (>= 1)
  BenchProgressFn progress;
};

// Relative t tolerance of "agrees with the first structure", the same as the
// Embree agreement test's (docs/oracle.md).
inline constexpr double kBenchTolerance = 1e-4;

struct BenchResult {
  std::string name;
  std::optional<double> buildSeconds;
  std::vector<double> mraysPerSecond;  // index i: repetition i
  double medianMraysPerSecond = 0.0;
  double minMraysPerSecond = 0.0;
  double maxMraysPerSecond = 0.0;
  // The same passes timed by the calling thread's CPU clock: on a loaded machine
  // wall time includes waiting for a core, CPU time does not.
  std::vector<double> cpuMraysPerSecond;
  double medianCpuMraysPerSecond = 0.0;
  uint64_t hits = 0;
  // Order-sensitive hash of every ray's (hit?, prim, bits of t): equal checksums
  // mean bit-identical hit lists.
  uint64_t checksum = 0;
  // Against the first structure, ray by ray (the first agrees with itself):
  uint64_t sameHitMiss = 0;  // both hit or both miss
  uint64_t agreeing = 0;     // same hit/miss and, if both hit, t within kBenchTolerance relative
  uint64_t identical = 0;    // same hit/miss and, if both hit, same prim and bits of t
  // Every timed pass found the same number of hits as the checked pass.
  bool deterministic = true;
};

struct BenchReport {
  size_t triangles = 0;
  size_t rays = 0;
  int repetitions = 0;
  std::vector<BenchResult> results;  // in the order the structures were given
};

// Measures every subject over `rays`, single-threaded on the calling thread.
// Throughput is rays / wall-clock seconds (steady_clock), plus the same over the
// thread's CPU time. One untimed pass per structure first
// records hits, checksum and agreement (and warms the caches); then each
// repetition times one pass of every structure, rotating the order by one per
// repetition so slow phases of the machine spread over all of them. Throws
// InputError on no subjects, a null accel, or repetitions < 1.
BenchReport runBenchmark(const Scene& scene, const std::vector<Ray>& rays,
                         const std::vector<BenchSubject>& subjects, const BenchOptions& options = {});

// Builds each candidate (timed, one at a time), then benchmarks as above.
BenchReport runBenchmark(const Scene& scene, const std::vector<Ray>& rays,
                         const std::vector<BenchCandidate>& candidates, const BenchOptions& options = {});

}  // namespace lancer
