#include "common/sah.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <limits>

#include <fmt/format.h>

#include "common/error.h"

namespace lancer {

namespace {

int ceilLog2(size_t n) { return n <= 1 ? 0 : int(std::bit_width(n - 1)); }

struct Prim {
  Aabb box;
  glm::vec3 centroid;
  uint32_t index;
};

struct Builder {
  const SahOptions& options;
  std::vector<Prim>& prims;
  SahTree& tree;

  // Builds the subtree over prims[begin, end) at level `depth` (root = 1) and
  // returns its node index; children follow their parent, left subtree first.
  uint32_t build(size_t begin, size_t end, int depth) {
    const uint32_t index = uint32_t(tree.nodes.size());
    tree.nodes.emplace_back();
    tree.depth = std::max(tree.depth, depth);
    const size_t n = end - begin;

    Aabb box, centroids;
    for (size_t i = begin; i < end; ++i) {
      box.extend(prims[i].box);
      centroids.extend(prims[i].centroid);
    }
    tree.nodes[index].box = box;

    auto makeLeaf = [&] {
      SahNode& node = tree.nodes[index];
      node.begin = uint32_t(tree.order.size());
      for (size_t i = begin; i < end; ++i) tree.order.push_back(prims[i].index);
      node.end = uint32_t(tree.order.size());
      ++tree.leaves;
      return index;
    };
    if (n == 1) return makeLeaf();

    // Costs are kept multiplied by the node's area (no division), so flat or
    // point-like nodes compare without NaN.
    const float area = box.surfaceArea();
    const float leafCost = float(n) * area;
    int bestAxis = -1, bestBin = 0;
    float bestCost = std::numeric_limits<float>::infinity();
    auto binOf = [&](const glm::vec3& c, int axis, float scale) {
      return std::clamp(int((c[axis] - centroids.lo[axis]) * scale), 0, kSahBins - 1);
    };
    for (int axis = 0; axis < 3; ++axis) {
      const float extent = centroids.hi[axis] - centroids.lo[axis];
      if (!(extent > 0.0f)) continue;
      const float scale = float(kSahBins) / extent;
      std::array<Aabb, kSahBins> binBox;
      std::array<size_t, kSahBins> binCount{};
      for (size_t i = begin; i < end; ++i) {
        const int b = binOf(prims[i].centroid, axis, scale);
        ++binCount[b];
        binBox[b].extend(prims[i].box);
      }
      // Sweep from the right for the area and count right of each split plane.
      std::array<float, kSahBins> rightArea{};
      std::array<size_t, kSahBins> rightCount{};
      Aabb acc;
      size_t count = 0;
      for (int b = kSahBins - 1; b > 0; --b) {
        acc.extend(binBox[b]);
        count += binCount[b];
        rightArea[b] = acc.empty() ? 0.0f : acc.surfaceArea();
        rightCount[b] = count;
      }
      acc = Aabb{};
      count = 0;
      for (int b = 0; b < kSahBins - 1; ++b) {  // split between bin b and b + 1
        acc.extend(binBox[b]);
        count += binCount[b];
        if (count == 0 || rightCount[b + 1] == 0) continue;
        const float cost = options.traversalCost * area + float(count) * acc.surfaceArea() +
                           float(rightCount[b + 1]) * rightArea[b + 1];
        if (cost < bestCost) {
          bestCost = cost;
          bestAxis = axis;
          bestBin = b;
        }
      }
    }

    if (n <= size_t(options.leafSize) && (bestAxis < 0 || leafCost <= bestCost)) return makeLeaf();

    // Depth guard: an SAH split may peel off one primitive per level. Once the
    // remaining levels could exceed maxDepth, halve instead.
    const bool forceMedian = depth + 1 + ceilLog2(n) > options.maxDepth;
    size_t mid;
    int splitAxis;
    if (bestAxis < 0 || forceMedian) {
      // Median split: also the fallback when every centroid coincides.
      const glm::vec3 d = centroids.diagonal();
      splitAxis = (d.x >= d.y && d.x >= d.z) ? 0 : (d.y >= d.z ? 1 : 2);
      mid = begin + n / 2;
      std::nth_element(prims.begin() + ptrdiff_t(begin), prims.begin() + ptrdiff_t(mid),
                       prims.begin() + ptrdiff_t(end),
                       [splitAxis](const Prim& a, const Prim& b) { return a.centroid[splitAxis] < b.centroid[splitAxis]; });
    } else {
      splitAxis = bestAxis;
      const float scale = float(kSahBins) / (centroids.hi[bestAxis] - centroids.lo[bestAxis]);
      auto it = std::partition(prims.begin() + ptrdiff_t(begin), prims.begin() + ptrdiff_t(end),
                               [&](const Prim& p) { return binOf(p.centroid, bestAxis, scale) <= bestBin; });
      mid = size_t(it - prims.begin());
    }
    assert(mid > begin && mid < end);

    build(begin, mid, depth + 1);
    const uint32_t right = build(mid, end, depth + 1);
    SahNode& node = tree.nodes[index];
    node.leaf = false;
    node.right = right;
    node.axis = uint8_t(splitAxis);
    node.begin = tree.nodes[index + 1].begin;
    node.end = tree.nodes[right].end;
    return index;
  }
};

}  // namespace

SahTree buildSah(std::span<const Aabb> boxes, const SahOptions& options) {
  if (options.leafSize < 1) throw InputError(fmt::format("BVH leaf size {} must be at least 1", options.leafSize));
  const int needed = 1 + ceilLog2(boxes.size());
  if (options.maxDepth < needed) {
    throw InputError(fmt::format("a BVH over {} primitives needs {} levels; the limit is {}", boxes.size(), needed,
                                 options.maxDepth));
  }
  SahTree tree;
  if (boxes.empty()) return tree;
  std::vector<Prim> prims(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) prims[i] = Prim{boxes[i], boxes[i].center(), uint32_t(i)};
  tree.nodes.reserve(2 * boxes.size());
  tree.order.reserve(boxes.size());
  Builder{options, prims, tree}.build(0, boxes.size(), 1);
  return tree;
}

}  // namespace lancer
