#pragma once

// An octree image the formats do not allow, to see rt_octree's assertions
// fire (rt_octree_test.cpp, verilated_context_test.cpp): its interior nodes go
// one level deeper than kOctreeMaxDepth (a node one lattice unit wide split
// again). The ray from the corner at 0 along the diagonal enters child 0 at
// every level and trips a_stack_depth in DESCEND. Its recorded depth is the
// deepest allowed, as a corrupt memory image's would be: the descriptor's
// checkImage rejects an image that says it is too deep before any run.

#include <vector>

#include "golden/octree.h"

namespace lancer::rtltest {

inline fx::OctreeImage tooDeepOctreeImage() {
  fx::OctreeImage image;
  image.maxDepth = fx::kOctreeMaxDepth;
  image.leafSize = 1;
  image.depth = fx::kOctreeMaxDepth;  // what it claims; its nodes go one level deeper
  image.nodes.push_back(fx::OctreeNode{false, 1, 0});
  for (int level = 0; level <= fx::kOctreeMaxDepth; ++level) {
    const uint32_t base = uint32_t(image.nodes.size());
    for (int i = 0; i < 8; ++i) image.nodes.push_back(fx::OctreeNode{true, 0, 0});
    image.nodes[base] = fx::OctreeNode{false, base + 8, 0};  // child 0 splits again
  }
  for (int i = 0; i < 8; ++i) image.nodes.push_back(fx::OctreeNode{true, 0, 0});
  return image;
}

inline const std::vector<fx::QRay> kTooDeepDiagonalRay{
    fx::QRay{0, {0, 0, 0}, {fx::kDirMax, fx::kDirMax, fx::kDirMax}}};

}  // namespace lancer::rtltest
