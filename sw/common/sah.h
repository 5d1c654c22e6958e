#pragma once

// The binned-SAH builder of Lancer's BVHs: the reference's float BVH
// (ref/bvh.h) and the BVH unit's memory image (golden/bvh.h) are the same
// tree, built here from the primitives' boxes. The builder decides the
// topology only: which primitives each leaf holds and how interior nodes
// split; each user derives its own boxes (floats for the reference, lattice
// integers for the unit) and its own layout.

#include <cstdint>
#include <span>
#include <vector>

#include "common/aabb.h"

namespace lancer {

struct SahOptions {
  int leafSize = 4;   // a node with more primitives is always split
  int maxDepth = 64;  // levels from the root (1) to the deepest leaf
  // SAH cost of one node step relative to one primitive test.
  float traversalCost = 1.0f;
};

// One node, in depth-first order: an interior node's left child is the next
// node and `right` names the right one; a leaf holds order[begin, end).
struct SahNode {
  uint32_t begin = 0, end = 0;  // the primitives below, in `order`
  uint32_t right = 0;           // interior: index of the right child
  uint8_t axis = 0;             // interior: split axis
  bool leaf = true;
  Aabb box;                     // of the primitives below
  uint32_t count() const { return end - begin; }
};

struct SahTree {
  std::vector<SahNode> nodes;   // node 0 is the root; empty for no primitives
  std::vector<uint32_t> order;  // primitive ids, leaf by leaf
  int depth = 0;                // levels; a single leaf has depth 1
  size_t leaves = 0;
};

inline constexpr int kSahBins = 32;

// Binned SAH over the centroids (kSahBins bins per axis). A node becomes a
// leaf when it holds one primitive, or at most leafSize and no split is
// cheaper; once the remaining levels could exceed maxDepth it is halved at the
// median instead (ceil(log2 n) more levels), so the tree never exceeds
// maxDepth as long as maxDepth > ceil(log2 n). Throws InputError for
// leafSize < 1 or a maxDepth too small for the primitives.
SahTree buildSah(std::span<const Aabb> boxes, const SahOptions& options);

}  // namespace lancer
