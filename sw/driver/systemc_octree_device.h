#pragma once

#include "driver/systemc_traversal_device.h"

namespace lancer {

namespace sc {
struct rt_octree_unit;
}  // namespace sc

// The octree unit in SystemC (systemc/octree/, sw/driver/systemc_traversal_device.h):
// "systemc" (rt_octree_model) and "rtl-systemc" (Vrt_octree_sc); no mixed
// implementation (Impl::ModelRtlIsect throws: rt_octree_model holds no rt_isect).
using SystemCOctreeDevice = SystemCTraversalDevice<fx::OctreeImage, sc::rt_octree_unit>;

}  // namespace lancer
