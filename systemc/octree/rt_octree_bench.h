#pragma once

#include <utility>

#include <systemc>

#include "octree/rt_octree_mem.h"
#include "octree/rt_octree_tb.h"
#include "octree/rt_octree_types.h"

namespace lancer::sc {

// rt_octree_bench: one implementation of rt_octree (Dut: rt_octree_model or
// the Verilated Vrt_octree_sc) with its testbench and its memory, on signals
// named after the RTL ports they carry. The DUT, the testbench and the memory
// have the same port names, so one binding serves all three: the binding below
// is the wiring diagram (traversal unit <-> memory, rays in, results and visits out).
template <class Dut>
class rt_octree_bench : public sc_core::sc_module {
 public:
  sc_core::sc_signal<bool> clk_i{"clk_i"};
  sc_core::sc_signal<bool> rst_ni{"rst_ni"};
  sc_core::sc_signal<octree::cfg_slots_t> cfg_slots_i{"cfg_slots_i"};
  sc_core::sc_signal<octree::node_t> cfg_root_i{"cfg_root_i"};
  sc_core::sc_signal<bool> ray_valid_i{"ray_valid_i"};
  sc_core::sc_signal<bool> ray_ready_o{"ray_ready_o"};
  sc_core::sc_signal<isect_ray_t> ray_data_i{"ray_data_i"};
  sc_core::sc_signal<bool> res_valid_o{"res_valid_o"};
  sc_core::sc_signal<bool> res_ready_i{"res_ready_i"};
  sc_core::sc_signal<octree::res_t> res_data_o{"res_data_o"};
  sc_core::sc_signal<bool> visit_valid_o{"visit_valid_o"};
  sc_core::sc_signal<bool> visit_ready_i{"visit_ready_i"};
  sc_core::sc_signal<octree::visit_t> visit_data_o{"visit_data_o"};
  sc_core::sc_signal<bool> node_req_valid_o{"node_req_valid_o"};
  sc_core::sc_signal<bool> node_req_ready_i{"node_req_ready_i"};
  sc_core::sc_signal<octree::mem_addr_t> node_req_addr_o{"node_req_addr_o"};
  sc_core::sc_signal<octree::slot_t> node_req_tag_o{"node_req_tag_o"};
  sc_core::sc_signal<bool> node_rsp_valid_i{"node_rsp_valid_i"};
  sc_core::sc_signal<octree::group_t> node_rsp_data_i{"node_rsp_data_i"};
  sc_core::sc_signal<octree::slot_t> node_rsp_tag_i{"node_rsp_tag_i"};
  sc_core::sc_signal<bool> idx_req_valid_o{"idx_req_valid_o"};
  sc_core::sc_signal<bool> idx_req_ready_i{"idx_req_ready_i"};
  sc_core::sc_signal<octree::mem_addr_t> idx_req_addr_o{"idx_req_addr_o"};
  sc_core::sc_signal<octree::slot_t> idx_req_tag_o{"idx_req_tag_o"};
  sc_core::sc_signal<bool> idx_rsp_valid_i{"idx_rsp_valid_i"};
  sc_core::sc_signal<octree::idx_data_t> idx_rsp_data_i{"idx_rsp_data_i"};
  sc_core::sc_signal<octree::slot_t> idx_rsp_tag_i{"idx_rsp_tag_i"};
  sc_core::sc_signal<bool> tri_req_valid_o{"tri_req_valid_o"};
  sc_core::sc_signal<bool> tri_req_ready_i{"tri_req_ready_i"};
  sc_core::sc_signal<octree::mem_addr_t> tri_req_addr_o{"tri_req_addr_o"};
  sc_core::sc_signal<octree::slot_t> tri_req_tag_o{"tri_req_tag_o"};
  sc_core::sc_signal<bool> tri_rsp_valid_i{"tri_rsp_valid_i"};
  sc_core::sc_signal<isect_tri_t> tri_rsp_data_i{"tri_rsp_data_i"};
  sc_core::sc_signal<octree::slot_t> tri_rsp_tag_i{"tri_rsp_tag_i"};
  sc_core::sc_signal<bool> perf_isect_fire_o{"perf_isect_fire_o"};
  sc_core::sc_signal<bool> perf_step_ready_o{"perf_step_ready_o"};

  rt_octree_tb u_tb{"u_tb"};
  rt_octree_mem u_mem{"u_mem"};
  Dut u_dut;

  template <class... DutArgs>
  explicit rt_octree_bench(sc_core::sc_module_name name, DutArgs&&... args)
      : sc_core::sc_module(name), u_dut("u_dut", std::forward<DutArgs>(args)...) {
    // The DUT: every port.
    u_dut.clk_i(clk_i);
    u_dut.rst_ni(rst_ni);
    u_dut.cfg_slots_i(cfg_slots_i);
    u_dut.cfg_root_i(cfg_root_i);
    u_dut.ray_valid_i(ray_valid_i);
    u_dut.ray_ready_o(ray_ready_o);
    u_dut.ray_data_i(ray_data_i);
    u_dut.res_valid_o(res_valid_o);
    u_dut.res_ready_i(res_ready_i);
    u_dut.res_data_o(res_data_o);
    u_dut.visit_valid_o(visit_valid_o);
    u_dut.visit_ready_i(visit_ready_i);
    u_dut.visit_data_o(visit_data_o);
    bindMemoryPorts(u_dut);
    u_dut.perf_isect_fire_o(perf_isect_fire_o);
    u_dut.perf_step_ready_o(perf_step_ready_o);

    // The memory: the three read ports.
    u_mem.clk_i(clk_i);
    bindMemoryPorts(u_mem);

    // The testbench: clock, reset, configuration, streams; observes the memory ports.
    u_tb.clk_i(clk_i);
    u_tb.rst_ni(rst_ni);
    u_tb.cfg_slots_i(cfg_slots_i);
    u_tb.cfg_root_i(cfg_root_i);
    u_tb.ray_valid_i(ray_valid_i);
    u_tb.ray_ready_o(ray_ready_o);
    u_tb.ray_data_i(ray_data_i);
    u_tb.res_valid_o(res_valid_o);
    u_tb.res_ready_i(res_ready_i);
    u_tb.res_data_o(res_data_o);
    u_tb.visit_valid_o(visit_valid_o);
    u_tb.visit_ready_i(visit_ready_i);
    u_tb.visit_data_o(visit_data_o);
    u_tb.node_req_valid_o(node_req_valid_o);
    u_tb.node_req_addr_o(node_req_addr_o);
    u_tb.node_req_tag_o(node_req_tag_o);
    u_tb.node_rsp_valid_i(node_rsp_valid_i);
    u_tb.idx_req_valid_o(idx_req_valid_o);
    u_tb.idx_req_addr_o(idx_req_addr_o);
    u_tb.idx_req_tag_o(idx_req_tag_o);
    u_tb.idx_rsp_valid_i(idx_rsp_valid_i);
    u_tb.tri_req_valid_o(tri_req_valid_o);
    u_tb.tri_req_addr_o(tri_req_addr_o);
    u_tb.tri_req_tag_o(tri_req_tag_o);
    u_tb.tri_rsp_valid_i(tri_rsp_valid_i);
    u_tb.perf_isect_fire_o(perf_isect_fire_o);
    u_tb.perf_step_ready_o(perf_step_ready_o);
  }

 private:
  template <class M>
  void bindMemoryPorts(M& m) {
    m.node_req_valid_o(node_req_valid_o);
    m.node_req_ready_i(node_req_ready_i);
    m.node_req_addr_o(node_req_addr_o);
    m.node_req_tag_o(node_req_tag_o);
    m.node_rsp_valid_i(node_rsp_valid_i);
    m.node_rsp_data_i(node_rsp_data_i);
    m.node_rsp_tag_i(node_rsp_tag_i);
    m.idx_req_valid_o(idx_req_valid_o);
    m.idx_req_ready_i(idx_req_ready_i);
    m.idx_req_addr_o(idx_req_addr_o);
    m.idx_req_tag_o(idx_req_tag_o);
    m.idx_rsp_valid_i(idx_rsp_valid_i);
    m.idx_rsp_data_i(idx_rsp_data_i);
    m.idx_rsp_tag_i(idx_rsp_tag_i);
    m.tri_req_valid_o(tri_req_valid_o);
    m.tri_req_ready_i(tri_req_ready_i);
    m.tri_req_addr_o(tri_req_addr_o);
    m.tri_req_tag_o(tri_req_tag_o);
    m.tri_rsp_valid_i(tri_rsp_valid_i);
    m.tri_rsp_data_i(tri_rsp_data_i);
    m.tri_rsp_tag_i(tri_rsp_tag_i);
  }
};

}  // namespace lancer::sc
