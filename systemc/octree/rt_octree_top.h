#pragma once

#include "common/rt_trav_top.h"
#include "octree/rt_octree_unit.h"

namespace lancer::sc {

// rt_octree's SystemC system (common/rt_trav_top.h): the cycle model
// rt_octree_model (rt_isect's timing inside) and Vrt_octree_sc
// (rtl/octree/rt_octree.sv with its rt_isect, Verilated with --sc), each on its bench.
using rt_octree_top = rt_trav_top<rt_octree_unit>;
using rt_octree_impl = rt_trav_impl;
using rt_octree_tb = rt_trav_tb<rt_octree_unit>;
using rt_octree_mem = rt_trav_mem<rt_octree_unit>;

}  // namespace lancer::sc
