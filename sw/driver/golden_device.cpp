#include "driver/golden_device.h"

#include "golden/isect.h"
#include "golden/quadric.h"

namespace lancer {

namespace {

// The ideal timing of a pipeline of `latency` stages with initiation interval 1.
StreamStats idealStats(size_t requests, int latency) {
  StreamStats stats;
  stats.requests = stats.results = requests;
  stats.cycles = requests == 0 ? 0 : requests + uint64_t(latency);
  stats.cycleAccurate = false;
  return stats;
}

}  // namespace

StreamStats GoldenIsectDevice::run(std::span<const IsectRequest> requests,
                                   std::vector<fx::IsectResult>& results, const StreamOptions&) {
  results.reserve(results.size() + requests.size());
  for (const IsectRequest& r : requests) results.push_back(fx::intersect(r.ray, r.tri));
  return idealStats(requests.size(), fx::kIsectLatency);
}

StreamStats GoldenIsectDevice::runQuadrics(std::span<const QuadricRequest> requests,
                                           std::vector<fx::IsectResult>& results, const StreamOptions&) {
  results.reserve(results.size() + requests.size());
  for (const QuadricRequest& r : requests) results.push_back(fx::intersectQuadric(r.ray, r.quadric));
  return idealStats(requests.size(), fx::kQuadricLatency);
}

}  // namespace lancer
