#pragma once

#include <utility>

#include <systemc>

#include "common/rt_trav_mem.h"
#include "common/rt_trav_tb.h"
#include "common/rt_trav_unit.h"

namespace lancer::sc {

// rt_trav_bench: one implementation of a traversal unit (Dut: the unit's cycle
// model or its Verilated class; Unit: its traits, common/rt_trav_unit.h) with
// its testbench and its memory, on signals named after the RTL ports they
// carry. The testbench and the memory have the same port names, so one binding
// serves both and the DUT's common ports; the DUT's node/cell and
// configuration ports, whose C++ names are the unit's RTL names, are bound by
// Unit::bindUnitPorts. The binding below is the wiring diagram (traversal unit
// <-> memory, rays in, results and visits out).
template <class Unit, class Dut>
class rt_trav_bench : public sc_core::sc_module {
 public:
  using slot_t = typename Unit::slot_t;
  using mem_addr_t = typename Unit::mem_addr_t;

  sc_core::sc_signal<bool> clk_i{"clk_i"};
  sc_core::sc_signal<bool> rst_ni{"rst_ni"};
  sc_core::sc_signal<typename Unit::cfg_slots_t> cfg_slots_i{"cfg_slots_i"};
  sc_core::sc_signal<typename Unit::cfg_t> cfg_i{Unit::kNames.cfgPort};
  sc_core::sc_signal<bool> ray_valid_i{"ray_valid_i"};
  sc_core::sc_signal<bool> ray_ready_o{"ray_ready_o"};
  sc_core::sc_signal<isect_ray_t> ray_data_i{"ray_data_i"};
  sc_core::sc_signal<bool> res_valid_o{"res_valid_o"};
  sc_core::sc_signal<bool> res_ready_i{"res_ready_i"};
  sc_core::sc_signal<typename Unit::res_t> res_data_o{"res_data_o"};
  sc_core::sc_signal<bool> visit_valid_o{"visit_valid_o"};
  sc_core::sc_signal<bool> visit_ready_i{"visit_ready_i"};
  sc_core::sc_signal<typename Unit::visit_t> visit_data_o{"visit_data_o"};
  sc_core::sc_signal<bool> node_req_valid_o{portName(Unit::kNames.nodePort, "req_valid_o").c_str()};
  sc_core::sc_signal<bool> node_req_ready_i{portName(Unit::kNames.nodePort, "req_ready_i").c_str()};
  sc_core::sc_signal<mem_addr_t> node_req_addr_o{portName(Unit::kNames.nodePort, "req_addr_o").c_str()};
  sc_core::sc_signal<slot_t> node_req_tag_o{portName(Unit::kNames.nodePort, "req_tag_o").c_str()};
  sc_core::sc_signal<bool> node_rsp_valid_i{portName(Unit::kNames.nodePort, "rsp_valid_i").c_str()};
  sc_core::sc_signal<typename Unit::node_data_t> node_rsp_data_i{portName(Unit::kNames.nodePort, "rsp_data_i").c_str()};
  sc_core::sc_signal<slot_t> node_rsp_tag_i{portName(Unit::kNames.nodePort, "rsp_tag_i").c_str()};
  sc_core::sc_signal<bool> idx_req_valid_o{"idx_req_valid_o"};
  sc_core::sc_signal<bool> idx_req_ready_i{"idx_req_ready_i"};
  sc_core::sc_signal<mem_addr_t> idx_req_addr_o{"idx_req_addr_o"};
  sc_core::sc_signal<slot_t> idx_req_tag_o{"idx_req_tag_o"};
  sc_core::sc_signal<bool> idx_rsp_valid_i{"idx_rsp_valid_i"};
  sc_core::sc_signal<typename Unit::idx_data_t> idx_rsp_data_i{"idx_rsp_data_i"};
  sc_core::sc_signal<slot_t> idx_rsp_tag_i{"idx_rsp_tag_i"};
  sc_core::sc_signal<bool> tri_req_valid_o{"tri_req_valid_o"};
  sc_core::sc_signal<bool> tri_req_ready_i{"tri_req_ready_i"};
  sc_core::sc_signal<mem_addr_t> tri_req_addr_o{"tri_req_addr_o"};
  sc_core::sc_signal<slot_t> tri_req_tag_o{"tri_req_tag_o"};
  sc_core::sc_signal<bool> tri_rsp_valid_i{"tri_rsp_valid_i"};
  sc_core::sc_signal<isect_tri_t> tri_rsp_data_i{"tri_rsp_data_i"};
  sc_core::sc_signal<slot_t> tri_rsp_tag_i{"tri_rsp_tag_i"};
  sc_core::sc_signal<bool> perf_isect_fire_o{"perf_isect_fire_o"};
  sc_core::sc_signal<bool> perf_step_ready_o{"perf_step_ready_o"};

  rt_trav_tb<Unit> u_tb{"u_tb"};
  rt_trav_mem<Unit> u_mem{"u_mem"};
  Dut u_dut;

  template <class... DutArgs>
  explicit rt_trav_bench(sc_core::sc_module_name name, DutArgs&&... args)
      : sc_core::sc_module(name), u_dut("u_dut", std::forward<DutArgs>(args)...) {
    // The DUT: every port; the unit's own (configuration, node/cell port) by its traits.
    bindStreamPorts(u_dut);
    bindMemoryPorts(u_dut);
    Unit::bindUnitPorts(u_dut, *this);
    u_dut.perf_isect_fire_o(perf_isect_fire_o);
    u_dut.perf_step_ready_o(perf_step_ready_o);

    // The memory: the three read ports.
    u_mem.clk_i(clk_i);
    bindMemoryPorts(u_mem);
    bindNodePort(u_mem);

    // The testbench: clock, reset, configuration, streams; observes the memory ports.
    bindStreamPorts(u_tb);
    u_tb.cfg_i(cfg_i);
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

  // The node/cell port of a module whose C++ port names are the shared ones (node_*).
  template <class M>
  void bindNodePort(M& m) {
    m.node_req_valid_o(node_req_valid_o);
    m.node_req_ready_i(node_req_ready_i);
    m.node_req_addr_o(node_req_addr_o);
    m.node_req_tag_o(node_req_tag_o);
    m.node_rsp_valid_i(node_rsp_valid_i);
    m.node_rsp_data_i(node_rsp_data_i);
    m.node_rsp_tag_i(node_rsp_tag_i);
  }

 private:
  // Clock, reset, cfg_slots_i and the ray, result and visit streams (DUT and testbench).
  template <class M>
  void bindStreamPorts(M& m) {
    m.clk_i(clk_i);
    m.rst_ni(rst_ni);
    m.cfg_slots_i(cfg_slots_i);
    m.ray_valid_i(ray_valid_i);
    m.ray_ready_o(ray_ready_o);
    m.ray_data_i(ray_data_i);
    m.res_valid_o(res_valid_o);
    m.res_ready_i(res_ready_i);
    m.res_data_o(res_data_o);
    m.visit_valid_o(visit_valid_o);
    m.visit_ready_i(visit_ready_i);
    m.visit_data_o(visit_data_o);
  }

  // The index and triangle ports (DUT and memory).
  template <class M>
  void bindMemoryPorts(M& m) {
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
