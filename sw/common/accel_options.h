#pragma once

namespace lancer {

// How an acceleration structure is built, in software (sw/ref/) or as a
// hardware unit's memory image (sw/golden/): zero means "choose by the
// documented heuristic".
struct AccelOptions {
  int gridResolution = 0;  // voxels along the longest axis (1..1024)
  int octreeMaxDepth = 0;  // 1..kMaxOctreeDepth
  int octreeLeafSize = 0;  // split a node holding more triangles than this
  int octreeTreeletBytes = 0;  // octree unit: the treelet layout's node bytes per treelet (0: depth-first layout)
  int bvhLeafSize = 4;     // largest leaf the SAH builder may make
  int bvhTreeletBytes = 0; // BVH unit: the treelet layout's node bytes per treelet (0: depth-first layout)
};

}  // namespace lancer
