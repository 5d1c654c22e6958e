#include "ref/trace.h"

namespace lancer {

std::vector<std::optional<Hit>> traceRays(const Accel& accel, std::span<const Ray> rays,
                                          TraversalStats* stats,
                                          const std::function<void(size_t)>& onProgress) {
  constexpr size_t kChunk = 4096;
  std::vector<std::optional<Hit>> hits(rays.size());
  for (size_t begin = 0; begin < rays.size(); begin += kChunk) {
    const size_t end = std::min(rays.size(), begin + kChunk);
    for (size_t i = begin; i < end; ++i) hits[i] = accel.intersect(rays[i], stats);
    if (onProgress) onProgress(end - begin);
  }
  return hits;
}

}  // namespace lancer
