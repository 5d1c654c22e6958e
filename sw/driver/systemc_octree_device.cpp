#include "driver/systemc_octree_device.h"

#include "driver/systemc_traversal_device_impl.h"
#include "octree/rt_octree_unit.h"

namespace lancer {

template <>
void SystemCOctreeDevice::checkImage(const fx::OctreeImage& image) {
  if (image.nodes.empty()) throw InputError("the octree image has no root node");
  if (image.depth > fx::kOctreeMaxDepth) {
    throw InputError(fmt::format("octree depth {} exceeds the unit's stack ({} levels)", image.depth,
                                 fx::kOctreeMaxDepth));
  }
}

template class SystemCTraversalDevice<fx::OctreeImage, sc::rt_octree_unit>;

}  // namespace lancer
