#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "ref/accel.h"
#include "common/aabb.h"

namespace lancer {

// Deepest allowed leaf (the root is depth 0). Bounds the traversal stack.
inline constexpr int kMaxOctreeDepth = 16;

// An octree over the scene's bounding box (a box, not necessarily a cube), split
// at the mid-planes, traversed by the parametric algorithm of Revelles, Ureña and
// Lastra (2000). Returns bit-identical hits to BruteForce. A native quadric
// goes into every node its grown Quadric::bounds() overlaps, as a triangle's
// box does; a scene without quadrics runs a triangle-only traversal.
//
// Child numbering follows the paper: bit 4 is the upper x half, bit 2 upper y,
// bit 1 upper z. Nodes live in one flat vector; an internal node stores the index
// of its first child and its eight children are consecutive.
//
// A ray with a non-finite origin or direction, a zero direction or a NaN tMax
// hits nothing (BruteForce's answer for those is not meaningful).
class Octree final : public Accel {
 public:
  static constexpr int kDefaultMaxDepth = 10;
  static constexpr int kDefaultLeafSize = 8;

  // Throws InputError unless options.octreeMaxDepth is 0 (default) or
  // 1..kMaxOctreeDepth and options.octreeLeafSize is 0 (default) or positive.
  Octree(const Scene& scene, const AccelOptions& options);
  // The tree keeps a reference to the scene: a temporary would dangle.
  Octree(Scene&&, const AccelOptions&) = delete;

  std::string_view name() const override { return "octree"; }
  std::optional<Hit> intersect(const Ray& ray, TraversalStats* stats = nullptr) const override;
  bool intersectP(const Ray& ray) const override;

  int maxDepth() const { return maxDepth_; }  // the depth limit in force
  int leafSize() const { return leafSize_; }  // nodes with more primitives are split
  size_t nodeCount() const { return nodes_.size(); }
  int depth() const { return depth_; }  // the deepest leaf actually built
  size_t referenceCount() const { return triIndices_.size(); }
  // The subdivided box: the scene bounds grown by binningEpsilon().
  const Aabb& bounds() const { return bounds_; }

 private:
  static constexpr uint32_t kInternal = ~uint32_t(0);
  struct Node {
    uint32_t first = 0;  // internal: index of child 0; leaf: offset into triIndices_
    uint32_t count = 0;  // kInternal, or the leaf's number of primitives
  };

  void build(uint32_t node, const Aabb& box, std::vector<uint32_t> tris, int depth,
             const std::vector<Aabb>& grown);
  template <bool kAnyHit, bool kQuadrics>  // kQuadrics: the scene has quadrics
  std::optional<Hit> traverse(const Ray& ray, TraversalStats* stats) const;

  const Scene& scene_;
  int maxDepth_ = kDefaultMaxDepth;
  int leafSize_ = kDefaultLeafSize;
  int depth_ = 0;
  Aabb bounds_;
  std::vector<Node> nodes_;           // nodes_[0] is the root
  std::vector<uint32_t> triIndices_;  // leaf runs, ascending primitive ids
};

}  // namespace lancer
