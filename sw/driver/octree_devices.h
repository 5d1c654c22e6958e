#pragma once

// The octree unit's SystemC and Verilated devices by their types, for tests
// that need more than the model table's TraversalDevice (port traces).

#include "driver/systemc_traversal_device.h"
#include "driver/verilator_traversal_device.h"

class Vrt_octree;
namespace lancer::sc {
struct rt_octree_unit;
}

namespace lancer {

// "systemc" (rt_octree_model) and "rtl-systemc" (Vrt_octree_sc); no mixed
// implementation (Impl::ModelRtlIsect throws: rt_octree_model holds no rt_isect).
using SystemCOctreeDevice = SystemCTraversalDevice<fx::OctreeImage, sc::rt_octree_unit>;

// rt_octree (rtl/octree/rt_octree.sv, with its rt_isect): a node request at
// `first` returns the child group first .. first+7.
using VerilatorOctreeDevice = VerilatorTraversalDevice<Vrt_octree, fx::OctreeImage>;

}  // namespace lancer
