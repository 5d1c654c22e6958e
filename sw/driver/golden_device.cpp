#include "driver/golden_device.h"

#include "golden/isect.h"

namespace lancer {

StreamStats GoldenIsectDevice::run(std::span<const IsectRequest> requests,
                                   std::vector<fx::IsectResult>& results, const StreamOptions&) {
  results.reserve(results.size() + requests.size());
  for (const IsectRequest& r : requests) results.push_back(fx::intersect(r.ray, r.tri));
  StreamStats stats;
  stats.requests = stats.results = requests.size();
  stats.cycles = requests.empty() ? 0 : requests.size() + fx::kIsectLatency;
  stats.cycleAccurate = false;
  return stats;
}

}  // namespace lancer
