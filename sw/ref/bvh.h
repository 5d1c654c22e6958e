#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "ref/accel.h"
#include "ref/quadric.h"

namespace lancer {

// One node of the flattened BVH: 32 bytes, two per 64-byte cache line.
//
// Layout is depth-first: an interior node's first child is the next node in the
// array and `index` names the second, so the near child of a descent is usually
// already in cache. A leaf's primitives are contiguous in the BVH's reordered
// order (primIds()).
//
//   bytes  0..11  lo     float x3, exact min over the primitives' boxes below (a
//                        triangle's vertices, a quadric's Quadric::bounds())
//   bytes 12..23  hi     float x3, exact max over the same boxes
//   bytes 24..27  index  leaf: first primitive in the reordered array;
//                        interior: array index of the second child
//   bytes 28..29  count  leaf: primitive count, 1..Bvh::kMaxLeafSize; 0 = interior
//   byte  30      axis   interior: split axis (0..2), orders the children front to back
//   byte  31      pad    zero
struct alignas(32) BvhNode {
  glm::vec3 lo{0.0f};
  glm::vec3 hi{0.0f};
  uint32_t index = 0;
  uint16_t count = 0;
  uint8_t axis = 0;
  uint8_t pad = 0;

  bool isLeaf() const { return count != 0; }
};
static_assert(sizeof(BvhNode) == 32, "BvhNode must stay 32 bytes (two per cache line)");

// The reference bounding volume hierarchy: binned-SAH build, flattened
// depth-first nodes, ordered stack traversal with a conservative slab test.
// intersect() returns exactly what BruteForce returns (same prim, same bits of
// t, u, v): every triangle is tested with intersectTriangle(), and no box is
// culled that could hold a triangle the watertight test would accept at a t no
// larger than the current closest hit. docs/bvh.md gives the argument and its
// one known limit (ties involving hits at grazing angles under ~2 degrees).
// Native quadrics are built over by their Quadric::bounds() and tested in the
// leaves by the float reference's quadric test (ref/quadric.h); a scene
// without them runs the triangle-only loop.
class Bvh final : public Accel {
 public:
  static constexpr int kMaxLeafSize = 64;
  // Deepest tree the builder makes; the traversal stack has this many entries.
  static constexpr int kMaxDepth = 64;

  // Throws InputError unless 1 <= options.bvhLeafSize <= kMaxLeafSize. Copies
  // the triangles and quadrics, so `scene` need not outlive the BVH.
  Bvh(const Scene& scene, const AccelOptions& options);

  std::string_view name() const override { return "bvh"; }
  std::optional<Hit> intersect(const Ray& ray, TraversalStats* stats = nullptr) const override;
  bool intersectP(const Ray& ray) const override;

  size_t nodeCount() const { return nodes_.size(); }
  size_t leafCount() const { return leafCount_; }
  // Levels from the root to the deepest leaf; a single-leaf tree has depth 1.
  int depth() const { return depth_; }
  int leafSize() const { return leafSize_; }
  const std::vector<BvhNode>& nodes() const { return nodes_; }
  // The scene's primitive id (triangle, or T + quadric index) of each
  // reordered primitive, in leaf order.
  const std::vector<uint32_t>& primIds() const { return primIds_; }

 private:
  template <bool kAnyHit, bool kCount, bool kQuadrics, typename Slab>
  std::optional<Hit> traverse(const Ray& ray, const Slab& slab, TraversalStats* stats) const;
  template <bool kAnyHit, bool kQuadrics>  // kQuadrics: the scene has quadrics
  std::optional<Hit> dispatch(const Ray& ray, TraversalStats* stats) const;

  int leafSize_;
  int depth_ = 0;
  size_t leafCount_ = 0;
  std::vector<BvhNode> nodes_;
  std::vector<Triangle> triangles_;  // leaf-contiguous copy of the scene's triangles (a quadric's slot unused)
  std::vector<uint32_t> primIds_;    // scene id of the primitive at each leaf slot, reported in the hit
  Aabb bounds_;                      // of all primitives, for the per-ray slack
  uint32_t triangleCount_ = 0;       // ids from here on are quadrics
  std::vector<QuadricShape> quadrics_;  // the scene's quadrics, by id - triangleCount_
};

}  // namespace lancer
