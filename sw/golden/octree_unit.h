#pragma once

// The octree unit's descriptor (golden/unit.h lists what a descriptor provides).

#include <optional>

#include "golden/octree.h"
#include "golden/unit.h"

namespace lancer::fx {

// Its configuration port, cfg_root_i, carries the root's node record.
struct OctreeUnit : UnitBase<UnitKind::Octree, OctreeImage, OctreeNode, kOctreeNodeFields, kOctreeNodeFields,
                             kOctreeRecords, kOctreeFormatParams, kOctreeLatencies> {
  static constexpr UnitNames kNames =
      unitNames<"octree">({"nodes", "child group", "node table", "cfg_root_i", "node_steps", "node steps", "node_reads",
                           "child group reads"});
  static constexpr size_t kGroup = kOctreeChildren;  // a node read returns a child group
  static constexpr int kSetupLatency = kOctreeSetupLatency;

  static const std::vector<Node>& nodes(const Image& image) { return image.nodes; }
  static std::array<u128, 3> nodeValues(const Node& node) { return {node.leaf ? 1u : 0u, node.count, node.first}; }
  // The root's record; zero (the reset value) for an image without nodes.
  static std::array<u128, 3> configValues(const Image& image) {
    return image.nodes.empty() ? std::array<u128, 3>{} : nodeValues(image.nodes[0]);
  }

  // --octree-depth and --octree-leaf, or the heuristics where 0;
  // --octree-treelet-bytes: the treelet layout (layoutOctreeTreelets), blocks
  // of the most nodes (a power of two, whole child groups) in that many bytes.
  static std::vector<BuildOption> buildOptions() {
    return {{"--octree-depth", &AccelOptions::octreeMaxDepth,
             fmt::format("Octree maximum depth, 1..{} (default: from the triangle count)", kOctreeMaxDepth), true,
             {"octree_max_depth"}, true, kOctreeMaxDepth},
            {"--octree-leaf", &AccelOptions::octreeLeafSize,
             fmt::format("Octree leaf size: split nodes holding more triangles (default {})", kDefaultOctreeLeafSize),
             true, {"octree_leaf_size"}},
            {kTreeletFlag, &AccelOptions::octreeTreeletBytes,
             fmt::format("Octree unit's treelet layout: node bytes of a treelet block, at least one child group ({} "
                         "bytes); 0: depth-first (docs/scheduling.md)",
                         kGroupBytes),
             false, {"octree_treelet_bytes"}, false}};
  }
  static constexpr const char* kTreeletFlag = "--octree-treelet-bytes";
  static constexpr uint32_t kNodeBytes = uint32_t(kOctreeNodeBits + 7) / 8;
  static constexpr uint32_t kGroupBytes = kNodeBytes * uint32_t(kOctreeChildren);
  static Image build(std::vector<QTriangle> triangles, const AccelOptions& options, std::vector<QQuadric> quadrics = {}) {
    const size_t primitives = triangles.size() + quadrics.size();
    const int depth = options.octreeMaxDepth ? options.octreeMaxDepth : defaultOctreeDepth(primitives);
    const int leaf = options.octreeLeafSize ? options.octreeLeafSize : kDefaultOctreeLeafSize;
    Image image = buildOctreeImage(std::move(triangles), depth, leaf, std::move(quadrics));
    if (options.octreeTreeletBytes != 0) {
      layoutOctreeTreelets(image, treeletBlockNodes(kTreeletFlag, options.octreeTreeletBytes, kNodeBytes,
                                                    uint32_t(kOctreeChildren), "child group"));
    }
    return image;
  }

  static void checkImage(const Image& image, std::span<const QRay> rays) {
    if (image.nodes.empty()) throw InputError("the octree image has no nodes (node 0 is the root)");
    if (image.depth > kOctreeMaxDepth) {
      throw InputError(
          fmt::format("octree depth {} exceeds the unit's stack ({} levels)", image.depth, kOctreeMaxDepth));
    }
    checkNonZeroDirections(rays, "octree");
  }

  static TraversalTrace traverse(const Image& image, const QRay& ray) { return traverseOctree(image, ray); }
  // The treelet schedule (docs/scheduling.md): the unit suspends walks
  // (octree_walk_t) before a child-group read in another block of a treelet
  // layout, 2^shift node-table entries each (cfg_block_shift_i); a suspended
  // walk waits for the block of the group it reads next, and a ray queue holds
  // octreeSuspendedBits of it.
  static constexpr const auto& kWalkFieldList = kOctreeWalkFields;
  static constexpr int kBlockShiftBits = kOctreeBlockShiftBits;  // cfg_block_shift_i
  static WaitingWalk suspended(const Image& image, std::span<const u128> walk) {
    const OctreeWalk w = octreeWalkOf(walk, QRay{});  // (its block and depth need no ray)
    return {w.waitsFor(image), octreeSuspendedBits(w.stack.size())};
  }
  // The treelet layout's crossings of a ray's walk (none without the layout).
  static TreeletCrossings treeletCrossings(const Image& image, const QRay& ray) {
    return octreeTreeletCrossings(image, ray);
  }

  // The unit holds one child group: the one of the node it descended into
  // last (or refilled). Entering a node whose parent's group is not held costs
  // a refill read; every interior node entered costs the read of its children.
  class NodeReads {
   public:
    explicit NodeReads(const Image& image) : image_(image), parent_(image.nodes.size(), 0) {
      for (uint32_t i = 0; i < image.nodes.size(); ++i) {
        if (image.nodes[i].leaf) continue;
        for (uint32_t c = 0; c < uint32_t(kOctreeChildren); ++c) parent_[image.nodes[i].first + c] = i;
      }
    }
    uint64_t operator()(const TraversalTrace& trace) const {
      uint64_t reads = 0;
      std::optional<uint32_t> held;  // the node whose children are in the group buffer
      for (size_t k = 0; k < trace.visits.size(); ++k) {
        const uint32_t node = trace.visits[k];
        if (k > 0 && held != parent_[node]) {  // refill
          ++reads;
          held = parent_[node];
        }
        if (!image_.nodes[node].leaf) {
          ++reads;
          held = node;
        }
      }
      return reads;
    }

   private:
    const Image& image_;
    std::vector<uint32_t> parent_;
  };

  static std::vector<ImageCounter> imageCounters(const Image& image) {
    return {{"octree_depth", "octree depth", double(image.depth)},
            {"octree_max_depth", "octree max depth", double(image.maxDepth)},
            {"octree_leaf_size", "octree leaf size", double(image.leafSize)},
            {"octree_nodes", "octree nodes", double(image.nodes.size())},
            {"octree_treelet_bytes", "octree treelet block bytes", double(image.treeletNodes * kNodeBytes)},
            {"octree_treelets", "octree treelets", double(image.treelets)},
            {"octree_treelet_padding_nodes", "octree treelet padding nodes", double(image.paddingNodes)}};
  }
};

}  // namespace lancer::fx
