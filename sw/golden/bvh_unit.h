#pragma once

// The BVH unit's descriptor (golden/unit.h lists what a descriptor provides).

#include "golden/bvh.h"
#include "golden/unit.h"

namespace lancer::fx {

// Its configuration port, cfg_root_i, carries the root's reference.
struct BvhUnit : UnitBase<UnitKind::Bvh, BvhImage, BvhNode, kBvhNodeFields, kBvhRefFields, kBvhRecords,
                          kBvhFormatParams, kBvhLatencies> {
  static constexpr UnitNames kNames = unitNames<"bvh">(
      {"nodes", "node", "node table", "cfg_root_i", "node_steps", "node steps", "node_reads", "node reads"});
  static constexpr size_t kGroup = 1;  // a node read returns one node (both children's boxes)
  static constexpr int kSetupLatency = kBvhSetupLatency;

  static const std::vector<Node>& nodes(const Image& image) { return image.nodes; }
  // In kBvhNodeFields order, arrays element 0 first (element 3c + a for the planes).
  static std::array<u128, valueCount(kBvhNodeFields)> nodeValues(const Node& node) {
    std::array<u128, valueCount(kBvhNodeFields)> v{};
    size_t k = 0;
    for (int a = 0; a < 3; ++a) v[k++] = u128(node.base[a]);
    for (int a = 0; a < 3; ++a) v[k++] = u128(node.shift[a]);
    for (int c = 0; c < kBvhWidth; ++c)
      for (int a = 0; a < 3; ++a) v[k++] = node.lo[c][a];
    for (int c = 0; c < kBvhWidth; ++c)
      for (int a = 0; a < 3; ++a) v[k++] = node.hi[c][a];
    for (int c = 0; c < kBvhWidth; ++c) v[k++] = node.child[c].leaf ? 1u : 0u;
    for (int c = 0; c < kBvhWidth; ++c) v[k++] = node.child[c].count;
    for (int c = 0; c < kBvhWidth; ++c) v[k++] = node.child[c].first;
    return v;
  }
  static std::array<u128, 3> configValues(const Image& image) {
    return {image.root.leaf ? 1u : 0u, image.root.count, image.root.first};
  }

  // --bvh-leaf: the largest leaf the SAH builder may make; --bvh-treelet-bytes:
  // the treelet layout (layoutBvhTreelets), blocks of the most nodes (a power
  // of two) in that many bytes.
  static std::vector<BuildOption> buildOptions() {
    return {{"--bvh-leaf", &AccelOptions::bvhLeafSize,
             fmt::format("BVH unit's largest leaf, 1..{} triangles (default {})", kBvhMaxLeafSize,
                         kDefaultBvhLeafSize),
             true, {"bvh_leaf_size"}, true, kBvhMaxLeafSize},
            {kTreeletFlag, &AccelOptions::bvhTreeletBytes,
             fmt::format("BVH unit's treelet layout: node bytes of a treelet block, at least one node ({} bytes); "
                         "0: depth-first (docs/scheduling.md)", kNodeBytes),
             false, {"bvh_treelet_bytes"}, false}};
  }
  static constexpr const char* kTreeletFlag = "--bvh-treelet-bytes";
  static constexpr uint32_t kNodeBytes = uint32_t(kBvhNodeBits + 7) / 8;
  static_assert(AccelOptions{}.bvhLeafSize == kDefaultBvhLeafSize, "a replay omits --bvh-leaf at the default");
  static Image build(std::vector<QTriangle> triangles, const AccelOptions& options, std::vector<QQuadric> quadrics = {}) {
    Image image = buildBvhImage(std::move(triangles), options.bvhLeafSize ? options.bvhLeafSize : kDefaultBvhLeafSize,
                                std::move(quadrics));
    if (options.bvhTreeletBytes != 0) {
      layoutBvhTreelets(image, treeletBlockNodes(kTreeletFlag, options.bvhTreeletBytes, kNodeBytes, 1, "node"));
    }
    return image;
  }

  static void checkImage(const Image& image, std::span<const QRay> rays) {
    if (image.depth > kBvhMaxLevels) {
      throw InputError(fmt::format("BVH depth {} exceeds the unit's stack ({} entries: at most {} levels)",
                                   image.depth, kBvhStackDepth, kBvhMaxLevels));
    }
    if (!image.root.leaf && image.nodes.empty()) {
      throw InputError("the BVH image has an interior root but no nodes (node 0 is the root)");
    }
    checkNonZeroDirections(rays, "BVH");
  }

  static TraversalTrace traverse(const Image& image, const QRay& ray) { return traverseBvh(image, ray); }
  // The treelet schedule (docs/scheduling.md): the unit suspends walks
  // (bvh_walk_t) at the blocks of a treelet layout, 2^shift node-table entries
  // each (cfg_block_shift_i); a suspended walk waits for the block of the node
  // it enters next, and a ray queue holds bvhSuspendedBits of it.
  static constexpr const auto& kWalkFieldList = kBvhWalkFields;
  static constexpr int kBlockShiftBits = kBvhBlockShiftBits;  // cfg_block_shift_i
  static WaitingWalk suspended(const Image& image, std::span<const u128> walk) {
    const BvhWalk w = bvhWalkOf(walk, 0);
    return {w.waitsFor(image), bvhSuspendedBits(w.stack.size())};
  }
  // The treelet layout's crossings of a ray's walk (none without the layout).
  static TreeletCrossings treeletCrossings(const Image& image, const QRay& ray) { return bvhTreeletCrossings(image, ray); }

  // One node read per interior node entered (a leaf's reference is in its parent).
  struct NodeReads {
    explicit NodeReads(const Image&) {}
    uint64_t operator()(const TraversalTrace& trace) const {
      uint64_t reads = 0;
      for (uint32_t id : trace.visits) reads += (id & kBvhLeafVisit) ? 0 : 1;
      return reads;
    }
  };

  static std::vector<ImageCounter> imageCounters(const Image& image) {
    return {{"bvh_depth", "BVH depth", double(image.depth)},
            {"bvh_leaf_size", "BVH leaf size", double(image.leafSize)},
            {"bvh_nodes", "BVH interior nodes", double(image.nodes.size() - image.paddingNodes)},
            {"bvh_leaves", "BVH leaves", double(image.leaves)},
            {"bvh_treelet_bytes", "BVH treelet block bytes", double(image.treeletNodes * kNodeBytes)},
            {"bvh_treelets", "BVH treelets", double(image.treelets)},
            {"bvh_treelet_padding_nodes", "BVH treelet padding nodes", double(image.paddingNodes)}};
  }
};

}  // namespace lancer::fx
