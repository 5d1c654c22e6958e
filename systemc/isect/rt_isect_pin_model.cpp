#include "isect/rt_isect_pin_model.h"

namespace lancer::sc {

rt_isect_pin_model::rt_isect_pin_model(sc_core::sc_module_name name) : sc_core::sc_module(name) {
  SC_METHOD(clocked);
  sensitive << clk_i.pos() << rst_ni.neg();
  dont_initialize();

  // Initialized: req_ready_o is driven from the start, as the RTL's.
  SC_METHOD(comb);
  sensitive << res_ready_i << updated_;
}

void rt_isect_pin_model::clocked() {
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

void rt_isect_pin_model::comb() {
  model_.res_ready_i = res_ready_i.read();
  model_.settle();
  req_ready_o.write(model_.req_ready_o);
}

void rt_isect_pin_model::readInputs() {
  model_.req_valid_i = req_valid_i.read();
  if (model_.req_valid_i) {  // the model reads the request only when valid
    pinToValue<ISECT_RAY_W>(req_ray_i.read(), model_.req_ray_i.value);
    pinToValue<ISECT_TRI_W>(req_tri_i.read(), model_.req_tri_i.value);
  }
  model_.res_ready_i = res_ready_i.read();
}

void rt_isect_pin_model::writeOutputs(bool all) {
  if (all || lastResValid_ != model_.res_valid_o.value) {
    lastResValid_ = model_.res_valid_o;
    res_valid_o.write(lastResValid_);
  }
  if (all || lastResData_ != model_.res_data_o.value) {
    lastResData_ = model_.res_data_o;
    res_data_o.write(pinOf<ISECT_RES_W>(lastResData_));
  }
}

}  // namespace lancer::sc
