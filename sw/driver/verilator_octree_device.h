#pragma once

#include "driver/verilator_traversal_device.h"

class Vrt_octree;

namespace lancer {

extern template class VerilatorTraversalDevice<Vrt_octree, fx::OctreeImage>;

// rt_octree (rtl/octree/rt_octree.sv, with its rt_isect) behind OctreeDevice.
// A node request at `first` returns the child group first .. first+7; the
// run's configuration is the root's record (cfg_root_i = image.nodes[0]).
// Also throws InputError for a ray with a zero direction, an image without
// nodes or deeper than the unit's stack. Its traits are in verilator_octree_device.cpp.
class VerilatorOctreeDevice final : public VerilatorTraversalDevice<Vrt_octree, fx::OctreeImage> {};

}  // namespace lancer
