#pragma once

#include <systemc>

#include "base/rt_value.h"
#include "isect/rt_isect_model.h"
#include "isect/rt_isect_ports.h"
#include "isect/rt_isect_types.h"

namespace lancer::sc {

// rt_isect_pin_model: the cycle model rt_isect_model bound to sc_in/sc_out
// under the RTL's port names and Verilator's port types (rt_isect_types.h),
// so that it drops into the SystemC bench where Vrt_isect_sc does
// (rt_isect_bench): the pin-level model of "systemc-pins".
//
//   clocked   SC_METHOD on clk_i.posedge and rst_ni.negedge (the RTL's
//             asynchronous reset): the inputs copied into the model, its
//             reset() or clock(), the outputs that changed written back
//   comb      SC_METHOD on res_ready_i and on every clocked update: the
//             model's settle(), req_ready_o written
class rt_isect_pin_model : public sc_core::sc_module, public rt_isect_ports<sc_core::sc_in, sc_core::sc_out> {
 public:
  sc_core::sc_in<bool> clk_i{"clk_i"};
  sc_core::sc_in<bool> rst_ni{"rst_ni"};

  SC_HAS_PROCESS(rt_isect_pin_model);
  explicit rt_isect_pin_model(sc_core::sc_module_name name);

 private:
  void clocked();
  void comb();
  void readInputs();
  // Written only when changed (or after reset): a kernel write, an sc_bv's
  // above all, costs more than the comparison.
  void writeOutputs(bool all);

  rt_isect_model model_;
  // The registered outputs as last written.
  bool lastResValid_ = false;
  value_t<ISECT_RES_W> lastResData_{};
  sc_core::sc_event updated_;
};

}  // namespace lancer::sc
