#pragma once

#include <systemc>

#include "common/rt_trav_unit.h"
#include "isect/rt_isect_types.h"

namespace lancer::sc {

// rt_trav_shell: the ports every traversal unit has (rtl/lib/'s traversal
// shell: clock and reset, cfg_slots_i, the ray, result and visit streams, the
// index and triangle read ports, the performance outputs), under the RTL's
// names and with the types of the unit's traits (Unit, common/rt_trav_unit.h).
// A unit's cycle model derives from it and adds its own ports (the node/cell
// port, its configuration port); the Verilated class has the same ports by
// construction, so both bind in rt_trav_bench alike.
template <class Unit>
class rt_trav_shell : public sc_core::sc_module {
 public:
  // The unit's port types, for the derived model's own ports and registers.
  using cfg_slots_t = typename Unit::cfg_slots_t;
  using cfg_t = typename Unit::cfg_t;
  using slot_t = typename Unit::slot_t;
  using mem_addr_t = typename Unit::mem_addr_t;
  using idx_data_t = typename Unit::idx_data_t;
  using node_data_t = typename Unit::node_data_t;
  using res_t = typename Unit::res_t;
  using visit_t = typename Unit::visit_t;

  sc_core::sc_in<bool> clk_i{"clk_i"};
  sc_core::sc_in<bool> rst_ni{"rst_ni"};
  sc_core::sc_in<cfg_slots_t> cfg_slots_i{"cfg_slots_i"};

  sc_core::sc_in<bool> ray_valid_i{"ray_valid_i"};
  sc_core::sc_out<bool> ray_ready_o{"ray_ready_o"};
  sc_core::sc_in<isect_ray_t> ray_data_i{"ray_data_i"};

  sc_core::sc_out<bool> res_valid_o{"res_valid_o"};
  sc_core::sc_in<bool> res_ready_i{"res_ready_i"};
  sc_core::sc_out<res_t> res_data_o{"res_data_o"};

  sc_core::sc_out<bool> visit_valid_o{"visit_valid_o"};
  sc_core::sc_in<bool> visit_ready_i{"visit_ready_i"};
  sc_core::sc_out<visit_t> visit_data_o{"visit_data_o"};

  sc_core::sc_out<bool> idx_req_valid_o{"idx_req_valid_o"};
  sc_core::sc_in<bool> idx_req_ready_i{"idx_req_ready_i"};
  sc_core::sc_out<mem_addr_t> idx_req_addr_o{"idx_req_addr_o"};
  sc_core::sc_out<slot_t> idx_req_tag_o{"idx_req_tag_o"};
  sc_core::sc_in<bool> idx_rsp_valid_i{"idx_rsp_valid_i"};
  sc_core::sc_in<idx_data_t> idx_rsp_data_i{"idx_rsp_data_i"};
  sc_core::sc_in<slot_t> idx_rsp_tag_i{"idx_rsp_tag_i"};

  sc_core::sc_out<bool> tri_req_valid_o{"tri_req_valid_o"};
  sc_core::sc_in<bool> tri_req_ready_i{"tri_req_ready_i"};
  sc_core::sc_out<mem_addr_t> tri_req_addr_o{"tri_req_addr_o"};
  sc_core::sc_out<slot_t> tri_req_tag_o{"tri_req_tag_o"};
  sc_core::sc_in<bool> tri_rsp_valid_i{"tri_rsp_valid_i"};
  sc_core::sc_in<isect_tri_t> tri_rsp_data_i{"tri_rsp_data_i"};
  sc_core::sc_in<slot_t> tri_rsp_tag_i{"tri_rsp_tag_i"};

  sc_core::sc_out<bool> perf_isect_fire_o{"perf_isect_fire_o"};
  sc_core::sc_out<bool> perf_step_ready_o{"perf_step_ready_o"};

 protected:
  explicit rt_trav_shell(sc_core::sc_module_name name) : sc_core::sc_module(name) {}

  // A request FIFO's head (rt_mem_req) onto a read port's address and tag;
  // the valid is the model's to write.
  template <class Fifo>
  static void writeRequest(const Fifo& q, sc_core::sc_out<mem_addr_t>& addr, sc_core::sc_out<slot_t>& tag) {
    addr.write(mem_addr_t(q.front().addr));
    tag.write(slot_t(q.front().slot));
  }
};

}  // namespace lancer::sc
