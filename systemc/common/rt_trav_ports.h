#pragma once

// The ports every traversal unit has (rtl/lib/rt_trav_ports.svh and the
// shell's node port), declared once for each side that meets them: In and Out
// are what the unit's inputs and outputs are on that side, so one list serves
//   the unit's cycle model   <rt_value, rt_value, value_t> (base/rt_value.h: plain values)
//   its pin-level module     <sc_in, sc_out>
//   the memory               <sc_out, sc_in>   (node and memory ports)
//   the testbench            <sc_out, sc_in>   (host ports), <sc_in, sc_in> (node and memory ports, observed)
//   the bench                <rt_signal, rt_signal>
// Bits<W> is the type of a W-bit port: Verilator's --sc types (vl_port_t) on
// signals, value_t on plain values.
// Port names are the RTL's (the node port's prefix is the unit's: cell_* for
// rt_grid), and one bind function per group binds any side to a bench's
// signals, the Verilated class too, whose members carry the same names.

#include <systemc>

#include "base/rt_value.h"
#include "common/rt_trav_unit.h"
#include "isect/rt_isect_ports.h"
#include "isect/rt_isect_types.h"

namespace lancer::sc {

// Clock, reset, cfg_slots_i, the ray, result and visit streams, the performance outputs.
template <class Unit, template <class> class In, template <class> class Out, template <int> class Bits = vl_port_t>
struct rt_trav_host_ports {
  In<bool> clk_i{"clk_i"};
  In<bool> rst_ni{"rst_ni"};
  In<Bits<Unit::CFG_SLOTS_W>> cfg_slots_i{"cfg_slots_i"};

  In<bool> ray_valid_i{"ray_valid_i"};
  Out<bool> ray_ready_o{"ray_ready_o"};
  In<Bits<ISECT_RAY_W>> ray_data_i{"ray_data_i"};

  Out<bool> res_valid_o{"res_valid_o"};
  In<bool> res_ready_i{"res_ready_i"};
  Out<Bits<Unit::RESULT_W>> res_data_o{"res_data_o"};

  Out<bool> visit_valid_o{"visit_valid_o"};
  In<bool> visit_ready_i{"visit_ready_i"};
  Out<Bits<Unit::VISIT_W>> visit_data_o{"visit_data_o"};

  Out<bool> perf_isect_fire_o{"perf_isect_fire_o"};
  Out<bool> perf_step_ready_o{"perf_step_ready_o"};
};

// One read port's seven ports, <p>_req_valid_o .. <p>_rsp_tag_i: requests
// {addr, tag} valid/ready, responses {data, tag} without ready. (A macro: the
// names are the RTL's.)
#define LANCER_SC_READ_PORT(p, data_w)                                   \
  Out<bool> p##_req_valid_o{#p "_req_valid_o"};                          \
  In<bool> p##_req_ready_i{#p "_req_ready_i"};                           \
  Out<Bits<MEM_ADDR_W>> p##_req_addr_o{#p "_req_addr_o"};       \
  Out<Bits<Unit::SLOT_W>> p##_req_tag_o{#p "_req_tag_o"};             \
  In<bool> p##_rsp_valid_i{#p "_rsp_valid_i"};                           \
  In<Bits<data_w>> p##_rsp_data_i{#p "_rsp_data_i"};                           \
  In<Bits<Unit::SLOT_W>> p##_rsp_tag_i{#p "_rsp_tag_i"}

// Binds read port p of `a` to the same of `b`.
#define LANCER_SC_BIND_READ_PORT(a, b, p)                                                     \
  (a).p##_req_valid_o((b).p##_req_valid_o), (a).p##_req_ready_i((b).p##_req_ready_i),         \
      (a).p##_req_addr_o((b).p##_req_addr_o), (a).p##_req_tag_o((b).p##_req_tag_o),           \
      (a).p##_rsp_valid_i((b).p##_rsp_valid_i), (a).p##_rsp_data_i((b).p##_rsp_data_i),       \
      (a).p##_rsp_tag_i((b).p##_rsp_tag_i)

// The node read port (a grid's cells, an octree's child groups, a BVH's nodes).
template <class Unit, template <class> class In, template <class> class Out, template <int> class Bits = vl_port_t>
struct rt_trav_node_port {
  LANCER_SC_READ_PORT(node, Unit::NODE_DATA_W);
};

// The index and primitive read ports: the triangle port's request names the
// quadric table with tri_req_quadric_o, and a quadric's record comes back on
// quadric_rsp_* (rtl/lib/rt_trav_ports.svh).
template <class Unit, template <class> class In, template <class> class Out, template <int> class Bits = vl_port_t>
struct rt_trav_mem_ports {
  LANCER_SC_READ_PORT(idx, 32);
  LANCER_SC_READ_PORT(tri, ISECT_TRI_W);
  Out<bool> tri_req_quadric_o{"tri_req_quadric_o"};
  In<bool> quadric_rsp_valid_i{"quadric_rsp_valid_i"};
  In<Bits<ISECT_QUADRIC_W>> quadric_rsp_data_i{"quadric_rsp_data_i"};
  In<Bits<Unit::SLOT_W>> quadric_rsp_tag_i{"quadric_rsp_tag_i"};
};

// All of them: what a unit's cycle model, its pin-level module, the
// testbench's side of it and the bench's wires each hold.
template <class Unit, template <class> class In, template <class> class Out, template <int> class Bits = vl_port_t>
struct rt_trav_unit_ports : rt_trav_host_ports<Unit, In, Out, Bits>,
                            rt_trav_node_port<Unit, In, Out, Bits>,
                            rt_trav_mem_ports<Unit, In, Out, Bits> {};

// Binds one side's ports (a module's, or a parent's) to another's of the same
// names (a bench's signals). The node port of a unit whose C++ names are not
// node_* (rt_grid's Verilated class) is its traits' to bind (bindUnitPorts).
template <class A, class B>
void bindNodePort(A& a, B& b) {
  LANCER_SC_BIND_READ_PORT(a, b, node);
}

template <class A, class B>
void bindMemPorts(A& a, B& b) {
  LANCER_SC_BIND_READ_PORT(a, b, idx);
  LANCER_SC_BIND_READ_PORT(a, b, tri);
  a.tri_req_quadric_o(b.tri_req_quadric_o);
  a.quadric_rsp_valid_i(b.quadric_rsp_valid_i);
  a.quadric_rsp_data_i(b.quadric_rsp_data_i);
  a.quadric_rsp_tag_i(b.quadric_rsp_tag_i);
}

template <class A, class B>
void bindHostPorts(A& a, B& b) {
  a.clk_i(b.clk_i);
  a.rst_ni(b.rst_ni);
  a.cfg_slots_i(b.cfg_slots_i);
  a.ray_valid_i(b.ray_valid_i);
  a.ray_ready_o(b.ray_ready_o);
  a.ray_data_i(b.ray_data_i);
  a.res_valid_o(b.res_valid_o);
  a.res_ready_i(b.res_ready_i);
  a.res_data_o(b.res_data_o);
  a.visit_valid_o(b.visit_valid_o);
  a.visit_ready_i(b.visit_ready_i);
  a.visit_data_o(b.visit_data_o);
  a.perf_isect_fire_o(b.perf_isect_fire_o);
  a.perf_step_ready_o(b.perf_step_ready_o);
}

}  // namespace lancer::sc
