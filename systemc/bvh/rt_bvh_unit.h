#pragma once

#include "bvh/rt_bvh_types.h"
#include "common/rt_trav_top.h"
#include "golden/bvh_unit.h"

namespace lancer::sc {

class rt_bvh_model;

// rt_bvh_unit: rt_bvh's traits for the shared traversal-unit modules
// (common/rt_trav_unit.h), from its descriptor: its cycle model and its
// cfg_root_i and node_* ports.
struct rt_bvh_unit : rt_trav_unit<bvh::RAYS_IN_FLIGHT, fx::BvhUnit> {
  using model_t = rt_bvh_model;

  template <class Dut, class Bench>
  static void bindUnitPorts(Dut& dut, Bench& b) {
    dut.cfg_root_i(b.cfg_i);
    b.bindNodePort(dut);
  }
};

// rt_bvh's SystemC system, testbench and memory (common/rt_trav_top.h).
using rt_bvh_top = rt_trav_top<rt_bvh_unit>;

}  // namespace lancer::sc
