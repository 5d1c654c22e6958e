#include "driver/traversal_device.h"

namespace lancer {

namespace {

// Runs `traverse` per ray; `nodeReads(trace)` counts the structure reads the
// hardware issues for it.
template <class Traverse, class NodeReads>
TraversalRunStats runGolden(std::span<const fx::QRay> rays, std::vector<fx::TraversalTrace>& traces,
                            Traverse traverse, NodeReads nodeReads) {
  TraversalRunStats stats;
  stats.cycleAccurate = false;
  traces.clear();
  traces.reserve(rays.size());
  for (const fx::QRay& ray : rays) {
    const fx::TraversalTrace& t = traces.emplace_back(traverse(ray));
    stats.steps += t.visits.size();
    stats.nodeReads += nodeReads(t);
    stats.indexReads += t.tests;
    stats.triangleReads += t.tests;
    stats.isectTests += t.tests;
  }
  stats.rays = rays.size();
  return stats;
}

}  // namespace

TraversalRunStats GoldenGridDevice::run(const fx::GridImage& image, std::span<const fx::QRay> rays,
                                        std::vector<fx::TraversalTrace>& traces, const TraversalRunOptions&) {
  return runGolden(
      rays, traces, [&](const fx::QRay& ray) { return fx::traverseGrid(image, ray); },
      [](const fx::TraversalTrace& t) { return t.visits.size(); });
}

TraversalRunStats GoldenOctreeDevice::run(const fx::OctreeImage& image, std::span<const fx::QRay> rays,
                                          std::vector<fx::TraversalTrace>& traces, const TraversalRunOptions&) {
  return runGolden(
      rays, traces, [&](const fx::QRay& ray) { return fx::traverseOctree(image, ray); },
      [&](const fx::TraversalTrace& t) {
        uint64_t interior = 0;
        for (uint32_t node : t.visits) interior += !image.nodes[node].leaf;
        return interior;
      });
}

}  // namespace lancer
