#include "driver/candidates.h"

#include <algorithm>
#include <limits>

namespace lancer {

namespace {

// Slab test in double against a box grown by `margin`; zero direction
// components are decided by the origin alone, so no 0 * inf appears.
bool touches(const BvhNode& node, const glm::dvec3& o, const glm::dvec3& d, double margin) {
  double tNear = 0.0, tFar = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    const double lo = double(node.lo[axis]) - margin, hi = double(node.hi[axis]) + margin;
    if (d[axis] == 0.0) {
      if (o[axis] < lo || o[axis] > hi) return false;
      continue;
    }
    double t0 = (lo - o[axis]) / d[axis], t1 = (hi - o[axis]) / d[axis];
    if (t0 > t1) std::swap(t0, t1);
    tNear = std::max(tNear, t0);
    tFar = std::min(tFar, t1);
    if (tNear > tFar) return false;
  }
  return true;
}

}  // namespace

CandidateSource bvhCandidates(const Bvh& bvh, float margin) {
  return [&bvh, margin](const Ray& ray, std::vector<uint32_t>& out) {
    const auto& nodes = bvh.nodes();
    const auto& prims = bvh.primIds();
    const glm::dvec3 o(ray.origin), d(ray.dir);
    uint32_t stack[Bvh::kMaxDepth + 1];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const BvhNode& node = nodes[stack[--top]];
      if (!touches(node, o, d, margin)) continue;
      if (node.isLeaf()) {
        for (uint32_t i = 0; i < node.count; ++i) out.push_back(prims[node.index + i]);
        continue;
      }
      // Depth-first layout: the first child follows its parent. Push the second first.
      const uint32_t self = uint32_t(&node - nodes.data());
      stack[top++] = node.index;
      stack[top++] = self + 1;
    }
  };
}

TriangleCandidates exactCandidates(const Bvh& bvh, const Aabb& sceneBounds) {
  const glm::vec3 largest = glm::max(glm::abs(sceneBounds.lo), glm::abs(sceneBounds.hi));
  const float extent = std::max({largest.x, largest.y, largest.z, glm::length(sceneBounds.diagonal())});
  return bvhCandidates(bvh, std::max(extent * 0x1p-30f, std::numeric_limits<float>::min()));
}

}  // namespace lancer
