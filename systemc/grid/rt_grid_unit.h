#pragma once

#include "common/rt_trav_top.h"
#include "golden/grid_unit.h"
#include "grid/rt_grid_types.h"

namespace lancer::sc {

class rt_grid_model;

// rt_grid_unit: rt_grid's traits for the shared traversal-unit modules
// (common/rt_trav_unit.h), from its descriptor: its cycle model, which can
// hold the Verilated rt_isect, its cfg_res_i and the node port.
struct rt_grid_unit : rt_trav_unit<RAYS_IN_FLIGHT, fx::GridUnit> {
  using model_t = rt_grid_model;

  template <class Dut, class Bench>
  static void bindUnitPorts(Dut& dut, Bench& b) {
    dut.cfg_res_i(b.cfg_i);
    b.bindNodePort(dut);
  }
};

// rt_grid's SystemC system, testbench and memory (common/rt_trav_top.h).
using rt_grid_top = rt_trav_top<rt_grid_unit>;

}  // namespace lancer::sc
