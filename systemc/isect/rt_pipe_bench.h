#pragma once

#include <systemc>

#include "isect/rt_isect_ports.h"
#include "isect/rt_isect_types.h"
#include "isect/rt_pipe_kind.h"
#include "isect/rt_pipe_tb.h"

namespace lancer::sc {

// rt_pipe_bench<Kind, Dut>: one implementation of a pipeline (Dut) on its own
// testbench and signals. Dut is rt_pipe_pin_model<Kind> or the Verilated class
// (Vrt_isect_sc, Vrt_quadric_sc): both have the RTL's port names and
// Verilator's port types, so one binding serves both, and the testbench, whose
// ports carry the same names, too. The binding below is the wiring diagram:
// every signal is named after the RTL port it connects.
template <class Kind, class Dut>
class rt_pipe_bench : public sc_core::sc_module, public Kind::template ports<rt_signal, rt_signal> {
 public:
  sc_core::sc_signal<bool> clk_i{"clk_i"};
  sc_core::sc_signal<bool> rst_ni{"rst_ni"};

  rt_pipe_tb<Kind> u_tb{"u_tb"};
  Dut u_dut{"u_dut"};

  explicit rt_pipe_bench(sc_core::sc_module_name name) : sc_core::sc_module(name) {
    bind(u_tb);
    bind(u_dut);
  }

 private:
  template <class M>
  void bind(M& m) {
    m.clk_i(clk_i);
    m.rst_ni(rst_ni);
    bindStreamPorts(m, *this);
    Kind::prim(m)(Kind::prim(*this));
  }
};

}  // namespace lancer::sc
