#pragma once

#include "bvh/rt_bvh_types.h"
#include "common/rt_trav_top.h"
#include "golden/bvh_unit.h"

namespace lancer::sc {

class rt_bvh_model;

// rt_bvh_unit: rt_bvh's traits for the shared traversal-unit modules
// (common/rt_trav_unit.h), from its descriptor: its cycle model, cfg_root_i and
// the node port.
struct rt_bvh_unit : rt_root_node_unit<bvh::RAYS_IN_FLIGHT, fx::BvhUnit, rt_bvh_model> {};

// rt_bvh's SystemC system, testbench and memory (common/rt_trav_top.h).
using rt_bvh_top = rt_trav_top<rt_bvh_unit>;

}  // namespace lancer::sc
