#pragma once

#include "common/rt_trav_top.h"
#include "golden/octree_unit.h"
#include "octree/rt_octree_types.h"

namespace lancer::sc {

class rt_octree_model;

// rt_octree_unit: rt_octree's traits for the shared traversal-unit modules
// (common/rt_trav_unit.h), from its descriptor: its cycle model and its
// cfg_root_i and node_* ports.
struct rt_octree_unit : rt_trav_unit<octree::RAYS_IN_FLIGHT, fx::OctreeUnit> {
  using model_t = rt_octree_model;

  template <class Dut, class Bench>
  static void bindUnitPorts(Dut& dut, Bench& b) {
    dut.cfg_root_i(b.cfg_i);
    b.bindNodePort(dut);
  }
};

// rt_octree's SystemC system, testbench and memory (common/rt_trav_top.h).
using rt_octree_top = rt_trav_top<rt_octree_unit>;

}  // namespace lancer::sc
