#include "ref/accel.h"

#include <limits>

#include <fmt/format.h>

#include "common/error.h"
#include "ref/bvh.h"
#include "ref/grid.h"
#include "ref/octree.h"

namespace lancer {

std::string_view toString(AccelKind kind) {
  switch (kind) {
    case AccelKind::Grid: return "grid";
    case AccelKind::Octree: return "octree";
    case AccelKind::Bvh: return "bvh";
    case AccelKind::Embree: return "embree";
  }
  return "?";
}

AccelKind parseAccelKind(std::string_view name) {
  for (AccelKind kind : {AccelKind::Grid, AccelKind::Octree, AccelKind::Bvh, AccelKind::Embree}) {
    if (toString(kind) == name) return kind;
  }
  throw InputError(fmt::format("unknown acceleration structure '{}' (expected grid, octree, bvh or embree)", name));
}

const ReferenceBuildOption* findReferenceBuildOption(int AccelOptions::*field) {
  static const ReferenceBuildOption kOptions[] = {
      {&AccelOptions::gridResolution,
       fmt::format("Grid voxels along the longest axis, 1..{} (default: from the triangle count)",
                   UniformGrid::kMaxResolution),
       UniformGrid::kMaxResolution},
      {&AccelOptions::octreeMaxDepth,
       fmt::format("Octree maximum depth, 1..{} (default {})", kMaxOctreeDepth, Octree::kDefaultMaxDepth),
       kMaxOctreeDepth},
      {&AccelOptions::octreeLeafSize,
       fmt::format("Octree leaf size: split nodes holding more triangles (default {})", Octree::kDefaultLeafSize),
       std::numeric_limits<int>::max()},
      {&AccelOptions::bvhLeafSize,
       fmt::format("BVH: the largest leaf the SAH builder may make, 1..{} triangles (default {})", Bvh::kMaxLeafSize,
                   AccelOptions{}.bvhLeafSize),
       Bvh::kMaxLeafSize},
  };
  for (const ReferenceBuildOption& option : kOptions) {
    if (option.field == field) return &option;
  }
  return nullptr;
}

}  // namespace lancer
