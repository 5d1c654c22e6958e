#pragma once

#include <systemc>

#include "isect/rt_isect_tb.h"
#include "isect/rt_isect_types.h"

namespace lancer::sc {

// rt_isect_bench: one implementation of rt_isect (Dut) on its own testbench and
// signals. Dut is rt_isect_model or the Verilated Vrt_isect_sc: both have the
// RTL's port names and Verilator's port types, so one binding serves both, and
// the testbench, whose ports carry the same names, too. The binding below is
// the wiring diagram: every signal is named after the RTL port it connects.
template <class Dut>
class rt_isect_bench : public sc_core::sc_module {
 public:
  sc_core::sc_signal<bool> clk_i{"clk_i"};
  sc_core::sc_signal<bool> rst_ni{"rst_ni"};
  sc_core::sc_signal<bool> req_valid_i{"req_valid_i"};
  sc_core::sc_signal<bool> req_ready_o{"req_ready_o"};
  sc_core::sc_signal<isect_ray_t> req_ray_i{"req_ray_i"};
  sc_core::sc_signal<isect_tri_t> req_tri_i{"req_tri_i"};
  sc_core::sc_signal<bool> res_valid_o{"res_valid_o"};
  sc_core::sc_signal<bool> res_ready_i{"res_ready_i"};
  sc_core::sc_signal<isect_res_t> res_data_o{"res_data_o"};

  rt_isect_tb u_tb{"u_tb"};
  Dut u_dut{"u_dut"};

  explicit rt_isect_bench(sc_core::sc_module_name name) : sc_core::sc_module(name) {
    bind(u_tb);
    bind(u_dut);
  }

 private:
  template <class M>
  void bind(M& m) {
    m.clk_i(clk_i);
    m.rst_ni(rst_ni);
    m.req_valid_i(req_valid_i);
    m.req_ready_o(req_ready_o);
    m.req_ray_i(req_ray_i);
    m.req_tri_i(req_tri_i);
    m.res_valid_o(res_valid_o);
    m.res_ready_i(res_ready_i);
    m.res_data_o(res_data_o);
  }
};

}  // namespace lancer::sc
