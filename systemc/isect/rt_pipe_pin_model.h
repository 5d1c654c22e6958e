#pragma once

#include <systemc>

#include "base/rt_value.h"
#include "isect/rt_isect_types.h"
#include "isect/rt_pipe_kind.h"

namespace lancer::sc {

// rt_pipe_pin_model<Kind>: a pipeline's cycle model (rt_isect_model or
// rt_quadric_model) bound to sc_in/sc_out under the RTL's port names and
// Verilator's port types (rt_isect_types.h), so that it drops into the SystemC
// bench where Vrt_isect_sc or Vrt_quadric_sc does (rt_pipe_bench): the
// pin-level model of "systemc-pins".
//
//   clocked   SC_METHOD on clk_i.posedge and rst_ni.negedge (the RTL's
//             asynchronous reset): the inputs copied into the model, its
//             reset() or clock(), the outputs that changed written back
//   comb      SC_METHOD on res_ready_i and on every clocked update: the
//             model's settle(), req_ready_o written
template <class Kind>
class rt_pipe_pin_model : public sc_core::sc_module,
                          public Kind::template ports<sc_core::sc_in, sc_core::sc_out> {
 public:
  sc_core::sc_in<bool> clk_i{"clk_i"};
  sc_core::sc_in<bool> rst_ni{"rst_ni"};

  SC_HAS_PROCESS(rt_pipe_pin_model);
  explicit rt_pipe_pin_model(sc_core::sc_module_name name) : sc_core::sc_module(name) {
    SC_METHOD(clocked);
    this->sensitive << clk_i.pos() << rst_ni.neg();
    this->dont_initialize();

    // Initialized: req_ready_o is driven from the start, as the RTL's.
    SC_METHOD(comb);
    this->sensitive << this->res_ready_i << updated_;
  }

 private:
  void clocked() {
    if (!rst_ni.read()) {
      model_.reset();
      writeOutputs(true);
    } else {
      readInputs();
      model_.clock();
      writeOutputs(false);
    }
    updated_.notify();  // immediate: comb() runs in this evaluation phase
  }

  void comb() {
    model_.res_ready_i = this->res_ready_i.read();
    model_.settle();
    this->req_ready_o.write(model_.req_ready_o);
  }

  void readInputs() {
    model_.req_valid_i = this->req_valid_i.read();
    if (model_.req_valid_i) {  // the model reads the request only when valid
      pinToValue<ISECT_RAY_W>(this->req_ray_i.read(), model_.req_ray_i.value);
      pinToValue<Kind::PRIM_W>(Kind::prim(*this).read(), Kind::prim(model_).value);
    }
    model_.res_ready_i = this->res_ready_i.read();
  }

  // Written only when changed (or after reset): a kernel write, an sc_bv's
  // above all, costs more than the comparison.
  void writeOutputs(bool all) {
    if (all || lastResValid_ != model_.res_valid_o.value) {
      lastResValid_ = model_.res_valid_o;
      this->res_valid_o.write(lastResValid_);
    }
    if (all || lastResData_ != model_.res_data_o.value) {
      lastResData_ = model_.res_data_o;
      this->res_data_o.write(pinOf<ISECT_RES_W>(lastResData_));
    }
  }

  typename Kind::model model_;
  // The registered outputs as last written.
  bool lastResValid_ = false;
  value_t<ISECT_RES_W> lastResData_{};
  sc_core::sc_event updated_;
};

}  // namespace lancer::sc
