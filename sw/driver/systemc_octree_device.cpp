#include "driver/systemc_octree_device.h"

#include "driver/systemc_traversal_device_impl.h"
#include "octree/rt_octree_unit.h"

namespace lancer {

template class SystemCTraversalDevice<fx::OctreeImage, sc::rt_octree_unit>;

template <>
std::unique_ptr<OctreeDevice> makeSystemCDevice<fx::OctreeUnit>(SystemCImpl impl) {
  return std::make_unique<SystemCOctreeDevice>(impl);
}
template <>
bool systemCRtlAvailable<fx::OctreeUnit>() {
  return SystemCOctreeDevice::rtlAvailable();
}

}  // namespace lancer
