#pragma once

#include "common/rt_trav_top.h"
#include "golden/grid_unit.h"
#include "grid/rt_grid_types.h"

namespace lancer::sc {

class rt_grid_model;

// rt_grid_unit: rt_grid's traits for the shared traversal-unit modules
// (common/rt_trav_unit.h), from its descriptor: its cycle model, which can
// hold the Verilated rt_isect, and its cfg_res_i and cell_* ports.
struct rt_grid_unit : rt_trav_unit<RAYS_IN_FLIGHT, fx::GridUnit> {
  using model_t = rt_grid_model;

  template <class Dut, class Bench>
  static void bindUnitPorts(Dut& dut, Bench& b) {
    dut.cfg_res_i(b.cfg_i);
    dut.cell_req_valid_o(b.node_req_valid_o);
    dut.cell_req_ready_i(b.node_req_ready_i);
    dut.cell_req_addr_o(b.node_req_addr_o);
    dut.cell_req_tag_o(b.node_req_tag_o);
    dut.cell_rsp_valid_i(b.node_rsp_valid_i);
    dut.cell_rsp_data_i(b.node_rsp_data_i);
    dut.cell_rsp_tag_i(b.node_rsp_tag_i);
  }
};

// rt_grid's SystemC system, testbench and memory (common/rt_trav_top.h).
using rt_grid_top = rt_trav_top<rt_grid_unit>;

}  // namespace lancer::sc
