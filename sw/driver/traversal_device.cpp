#include "driver/traversal_device.h"

#include <optional>

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

template <>
TraversalRunStats GoldenGridDevice::run(const fx::GridImage& image, std::span<const fx::QRay> rays,
                                        std::vector<fx::TraversalTrace>& traces, const TraversalRunOptions&) {
  return runGolden(
      rays, traces, [&](const fx::QRay& ray) { return fx::traverseGrid(image, ray); },
      [](const fx::TraversalTrace& t) { return t.visits.size(); });
}

template <>
TraversalRunStats GoldenOctreeDevice::run(const fx::OctreeImage& image, std::span<const fx::QRay> rays,
                                          std::vector<fx::TraversalTrace>& traces, const TraversalRunOptions&) {
  // The unit holds one child group: the one of the node it descended into
  // last (or refilled). Entering a node whose parent's group is not held costs
  // a refill read; every interior node entered costs the read of its children.
  std::vector<uint32_t> parent(image.nodes.size(), 0);
  for (uint32_t i = 0; i < image.nodes.size(); ++i) {
    if (!image.nodes[i].leaf) {
      for (uint32_t c = 0; c < uint32_t(fx::kOctreeChildren); ++c) parent[image.nodes[i].first + c] = i;
    }
  }
  return runGolden(
      rays, traces, [&](const fx::QRay& ray) { return fx::traverseOctree(image, ray); },
      [&](const fx::TraversalTrace& t) {
        uint64_t reads = 0;
        std::optional<uint32_t> held;  // the node whose children are in the group buffer
        for (size_t k = 0; k < t.visits.size(); ++k) {
          const uint32_t node = t.visits[k];
          if (k > 0 && held != parent[node]) {  // refill
            ++reads;
            held = parent[node];
          }
          if (!image.nodes[node].leaf) {
            ++reads;
            held = node;
          }
        }
        return reads;
      });
}

}  // namespace lancer
