#include "ref/benchmark.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <ctime>

#include <fmt/format.h>

#include "common/error.h"

namespace lancer {

namespace {

using Clock = std::chrono::steady_clock;

// FNV-1a over the bytes of 64-bit words: cheap, order-sensitive, stable across runs.
struct Checksum {
  uint64_t value = 0xcbf29ce484222325ull;
  void add(uint64_t word) {
    for (int i = 0; i < 8; ++i) {
      value ^= (word >> (8 * i)) & 0xffu;
      value *= 0x100000001b3ull;
    }
  }
};

// CPU time of the calling thread, in seconds.
double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double mrays(size_t rays, double seconds) { return seconds > 0.0 ? double(rays) / seconds * 1e-6 : 0.0; }

uint64_t hitWord(const std::optional<Hit>& hit) {
  if (!hit) return ~0ull;
  return (uint64_t(hit->prim) << 32) | std::bit_cast<uint32_t>(hit->t);
}

bool withinTolerance(float a, float b) {
  return std::abs(double(a) - double(b)) <= kBenchTolerance * std::max(std::abs(double(a)), std::abs(double(b)));
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

BenchReport runBenchmark(const Scene& scene, const std::vector<Ray>& rays,
                         const std::vector<BenchSubject>& subjects, const BenchOptions& options) {
  if (subjects.empty()) throw InputError("benchmark: no structures to measure");
  if (options.repetitions < 1) {
    throw InputError(fmt::format("benchmark: repetitions {} must be at least 1", options.repetitions));
  }
  for (const BenchSubject& s : subjects) {
    if (!s.accel) throw InputError(fmt::format("benchmark: structure '{}' was not built", s.name));
  }
  BenchReport report;
  report.triangles = scene.size();
  report.rays = rays.size();
  report.repetitions = options.repetitions;

  // Checked pass: what each structure answers, compared ray by ray with the first.
  std::vector<std::optional<Hit>> reference;
  for (size_t s = 0; s < subjects.size(); ++s) {
    BenchResult result;
    result.name = subjects[s].name;
    result.buildSeconds = subjects[s].buildSeconds;
    Checksum checksum;
    std::vector<std::optional<Hit>> hits(s == 0 ? rays.size() : 0);
    for (size_t r = 0; r < rays.size(); ++r) {
      const std::optional<Hit> hit = subjects[s].accel->intersect(rays[r]);
      checksum.add(hitWord(hit));
      result.hits += hit.has_value();
      const std::optional<Hit>& first = s == 0 ? hit : reference[r];
      if (hit.has_value() == first.has_value()) {
        ++result.sameHitMiss;
        const bool bothMiss = !hit;
        result.agreeing += bothMiss || withinTolerance(hit->t, first->t);
        result.identical += bothMiss || hitWord(hit) == hitWord(first);
      }
      if (s == 0) hits[r] = hit;
    }
    if (s == 0) reference = std::move(hits);
    result.checksum = checksum.value;
    report.results.push_back(std::move(result));
  }

  // Timed passes. Only the hit count leaves the loop, which keeps the work
  // observable without adding per-ray bookkeeping to the measurement.
  const int total = options.repetitions * int(subjects.size());
  int done = 0;
  for (int rep = 0; rep < options.repetitions; ++rep) {
    for (size_t k = 0; k < subjects.size(); ++k) {
      const size_t s = (k + size_t(rep)) % subjects.size();
      const Accel& accel = *subjects[s].accel;
      uint64_t hitCount = 0;
      const double cpuStart = threadCpuSeconds();
      const auto start = Clock::now();
      for (const Ray& ray : rays) hitCount += accel.intersect(ray).has_value();
      const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
      const double cpuSeconds = threadCpuSeconds() - cpuStart;
      BenchResult& result = report.results[s];
      result.mraysPerSecond.push_back(mrays(rays.size(), seconds));
      result.cpuMraysPerSecond.push_back(mrays(rays.size(), cpuSeconds));
      result.deterministic = result.deterministic && hitCount == result.hits;
      if (options.progress) options.progress(result.name, rep, ++done, total);
    }
  }
  for (BenchResult& result : report.results) {
    result.medianMraysPerSecond = median(result.mraysPerSecond);
    result.medianCpuMraysPerSecond = median(result.cpuMraysPerSecond);
    result.minMraysPerSecond = *std::min_element(result.mraysPerSecond.begin(), result.mraysPerSecond.end());
    result.maxMraysPerSecond = *std::max_element(result.mraysPerSecond.begin(), result.mraysPerSecond.end());
  }
  return report;
}

BenchReport runBenchmark(const Scene& scene, const std::vector<Ray>& rays,
                         const std::vector<BenchCandidate>& candidates, const BenchOptions& options) {
  std::vector<std::unique_ptr<Accel>> built;
  std::vector<BenchSubject> subjects;
  for (const BenchCandidate& c : candidates) {
    if (!c.build) throw InputError(fmt::format("benchmark: structure '{}' has no builder", c.name));
    const auto start = Clock::now();
    built.push_back(c.build());
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    subjects.push_back({c.name, built.back().get(), seconds});
  }
  return runBenchmark(scene, rays, subjects, options);
}

}  // namespace lancer
