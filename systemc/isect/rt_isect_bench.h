#pragma once

#include <systemc>

#include "isect/rt_isect_ports.h"
#include "isect/rt_isect_tb.h"
#include "isect/rt_isect_types.h"

namespace lancer::sc {

// rt_isect_bench: one implementation of rt_isect (Dut) on its own testbench and
// signals. Dut is rt_isect_pin_model or the Verilated Vrt_isect_sc: both have the
// RTL's port names and Verilator's port types, so one binding serves both, and
// the testbench, whose ports carry the same names, too. The binding below is
// the wiring diagram: every signal is named after the RTL port it connects.
template <class Dut>
class rt_isect_bench : public sc_core::sc_module, public rt_isect_signals {
 public:
  sc_core::sc_signal<bool> clk_i{"clk_i"};
  sc_core::sc_signal<bool> rst_ni{"rst_ni"};

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
    bindIsectPorts(m, *this);
  }
};

}  // namespace lancer::sc
