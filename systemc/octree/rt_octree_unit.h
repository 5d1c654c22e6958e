#pragma once

#include "common/rt_trav_top.h"
#include "golden/octree_unit.h"
#include "octree/rt_octree_types.h"

namespace lancer::sc {

class rt_octree_model;

// rt_octree_unit: rt_octree's traits for the shared traversal-unit modules
// (common/rt_trav_unit.h), from its descriptor: its cycle model, cfg_root_i and
// the node port.
struct rt_octree_unit : rt_root_node_unit<octree::RAYS_IN_FLIGHT, fx::OctreeUnit, rt_octree_model> {};

// rt_octree's SystemC system, testbench and memory (common/rt_trav_top.h).
using rt_octree_top = rt_trav_top<rt_octree_unit>;

}  // namespace lancer::sc
