#pragma once

// rt_trav_pin_model: a traversal unit's cycle model (Unit::model_t, plain
// C++ on plain values: common/rt_trav_shell_model.h) bound to sc_in/sc_out
// under the RTL's port names, so that it drops into the SystemC bench where
// the Verilated RTL does (rt_trav_bench): the pin-level co-simulation.
//
//   clocked   SC_METHOD on clk_i.posedge and rst_ni.negedge (the RTL's
//             asynchronous reset): the inputs copied into the model, its
//             reset() or clock(), the outputs that changed written back
//   comb      SC_METHOD on what the combinational outputs depend on (the
//             triangle response when the unit uses it in the cycle it
//             arrives, u_isect's req_ready_o when it is outside) and on every
//             clocked update: the model's settle()
//
// With rt_isect_impl::rtl the model's u_isect is the Verilated rt_isect on
// signals here (the mixed system): its ports are copied to and from the
// model's `isect` ports. A model's failure (std::runtime_error) becomes an
// SC_REPORT_ERROR under this module's name.

#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <systemc>

#include "common/rt_trav_ports.h"
#include "isect/rt_isect_rtl.h"

namespace lancer::sc {

template <class Unit>
class rt_trav_pin_model : public sc_core::sc_module, public rt_trav_unit_ports<Unit, sc_core::sc_in, sc_core::sc_out> {
  using model_t = typename Unit::model_t;

 public:
  sc_core::sc_in<typename Unit::cfg_t> cfg_i{Unit::kNames.cfgPort};

  SC_HAS_PROCESS(rt_trav_pin_model);
  explicit rt_trav_pin_model(sc_core::sc_module_name name, rt_isect_impl isect = rt_isect_impl::model)
      : sc_core::sc_module(name), model_(makeModel(isect)) {
    if (model_->outsideIsect()) {
      isect_ = std::make_unique<rt_isect_signals>();
      u_isect = make_rtl_isect("u_isect", this->clk_i, this->rst_ni, *isect_);
    }
    SC_METHOD(comb);
    this->sensitive << updated_;
    if constexpr (!model_t::kRegisteredResponses) {
      this->sensitive << this->tri_rsp_valid_i << this->tri_rsp_tag_i << this->tri_rsp_data_i;
      this->sensitive << this->quadric_rsp_valid_i << this->quadric_rsp_tag_i << this->quadric_rsp_data_i;
    }
    if (isect_) this->sensitive << isect_->req_ready_o;
    SC_METHOD(clocked);
    this->sensitive << this->clk_i.pos() << this->rst_ni.neg();
    this->dont_initialize();
  }

 private:
  // The model, with its u_isect inside or outside (whichever its constructor takes).
  static std::unique_ptr<model_t> makeModel(rt_isect_impl isect) {
    if constexpr (std::is_constructible_v<model_t, rt_isect_impl>) {
      return std::make_unique<model_t>(isect);
    } else {
      if (isect != rt_isect_impl::model) throw std::runtime_error(std::string(Unit::kNames.module) + "'s cycle model holds no Verilated rt_isect");
      return std::make_unique<model_t>();
    }
  }

  template <class F>
  void guarded(F f) {
    try {
      f();
    } catch (const std::runtime_error& e) {
      SC_REPORT_ERROR(this->name(), e.what());
    }
  }

  void clocked() {
    guarded([this] {
      readInputs();  // the outputs after reset follow the configuration (ray_ready_o: cfg_slots_i)
      if (!this->rst_ni.read()) {
        model_->reset();
        writeOutputs(true);
      } else {
        model_->clock();
        writeOutputs(false);
      }
    });
    updated_.notify();  // immediate: comb() runs in this evaluation phase
  }

  void comb() {
    guarded([this] {
      readPrimitiveResponse();
      if (isect_) model_->isect.req_ready_o = isect_->req_ready_o.read();
      model_->settle();
      write<1>(this->perf_isect_fire_o, model_->perf_isect_fire_o, last_.perf_isect_fire_o, !combWritten_);
      combWritten_ = true;
      if (isect_) {
        isect_->req_valid_i.write(model_->isect.req_valid_i);
        if (model_->isect.req_valid_i) {
          isect_->req_ray_i.write(pinOf<ISECT_RAY_W>(model_->isect.req_ray_i.value));
          isect_->req_tri_i.write(pinOf<ISECT_TRI_W>(model_->isect.req_tri_i.value));
        }
      }
    });
  }

  // The primitive port's response: a triangle's or a quadric's.
  void readPrimitiveResponse() {
    model_t& m = *model_;
    m.tri_rsp_valid_i = this->tri_rsp_valid_i.read();
    if (m.tri_rsp_valid_i) {
      pinToValue<ISECT_TRI_W>(this->tri_rsp_data_i.read(), m.tri_rsp_data_i.value);
      m.tri_rsp_tag_i = this->tri_rsp_tag_i.read();
    }
    m.quadric_rsp_valid_i = this->quadric_rsp_valid_i.read();
    if (m.quadric_rsp_valid_i) {
      pinToValue<ISECT_QUADRIC_W>(this->quadric_rsp_data_i.read(), m.quadric_rsp_data_i.value);
      m.quadric_rsp_tag_i = this->quadric_rsp_tag_i.read();
    }
  }

  void readInputs() {
    model_t& m = *model_;
    m.cfg_slots_i = this->cfg_slots_i.read();
    pinToValue<Unit::CFG_W>(cfg_i.read(), m.cfg_i.value);
    m.ray_valid_i = this->ray_valid_i.read();
    if (m.ray_valid_i) pinToValue<ISECT_RAY_W>(this->ray_data_i.read(), m.ray_data_i.value);
    m.res_ready_i = this->res_ready_i.read();
    m.visit_ready_i = this->visit_ready_i.read();
    m.node_req_ready_i = this->node_req_ready_i.read();
    m.node_rsp_valid_i = this->node_rsp_valid_i.read();
    if (m.node_rsp_valid_i) {
      pinToValue<Unit::NODE_DATA_W>(this->node_rsp_data_i.read(), m.node_rsp_data_i.value);
      m.node_rsp_tag_i = this->node_rsp_tag_i.read();
    }
    m.idx_req_ready_i = this->idx_req_ready_i.read();
    m.idx_rsp_valid_i = this->idx_rsp_valid_i.read();
    if (m.idx_rsp_valid_i) {
      m.idx_rsp_data_i = this->idx_rsp_data_i.read();
      m.idx_rsp_tag_i = this->idx_rsp_tag_i.read();
    }
    m.tri_req_ready_i = this->tri_req_ready_i.read();
    readPrimitiveResponse();
    if (isect_) {
      m.isect.req_ready_o = isect_->req_ready_o.read();
      m.isect.res_valid_o = isect_->res_valid_o.read();
      if (m.isect.res_valid_o) pinToValue<ISECT_RES_W>(isect_->res_data_o.read(), m.isect.res_data_o.value);
    }
  }

  // A W-bit output written when its value changed (or after reset): kernel
  // writes are most of a pin-level cycle's cost. `last` holds the value as
  // last written.
  template <int W>
  static void write(sc_core::sc_out<vl_port_t<W>>& pin, const rt_value<value_t<W>>& v, rt_value<value_t<W>>& last,
                    bool all) {
    if (!all && last.value == v.value) return;
    last.value = v.value;
    pin.write(pinOf<W>(v.value));
  }

  void writeOutputs(bool all) {
    model_t& m = *model_;
    constexpr int A = MEM_ADDR_W, S = Unit::SLOT_W;
    write<1>(this->ray_ready_o, m.ray_ready_o, last_.ray_ready_o, all);
    write<1>(this->res_valid_o, m.res_valid_o, last_.res_valid_o, all);
    write<Unit::RESULT_W>(this->res_data_o, m.res_data_o, last_.res_data_o, all);
    write<1>(this->visit_valid_o, m.visit_valid_o, last_.visit_valid_o, all);
    write<Unit::VISIT_W>(this->visit_data_o, m.visit_data_o, last_.visit_data_o, all);
    write<1>(this->perf_step_ready_o, m.perf_step_ready_o, last_.perf_step_ready_o, all);
    write<1>(this->node_req_valid_o, m.node_req_valid_o, last_.node_req_valid_o, all);
    write<A>(this->node_req_addr_o, m.node_req_addr_o, last_.node_req_addr_o, all);
    write<S>(this->node_req_tag_o, m.node_req_tag_o, last_.node_req_tag_o, all);
    write<1>(this->idx_req_valid_o, m.idx_req_valid_o, last_.idx_req_valid_o, all);
    write<A>(this->idx_req_addr_o, m.idx_req_addr_o, last_.idx_req_addr_o, all);
    write<S>(this->idx_req_tag_o, m.idx_req_tag_o, last_.idx_req_tag_o, all);
    write<1>(this->tri_req_valid_o, m.tri_req_valid_o, last_.tri_req_valid_o, all);
    write<A>(this->tri_req_addr_o, m.tri_req_addr_o, last_.tri_req_addr_o, all);
    write<S>(this->tri_req_tag_o, m.tri_req_tag_o, last_.tri_req_tag_o, all);
    write<1>(this->tri_req_quadric_o, m.tri_req_quadric_o, last_.tri_req_quadric_o, all);
    if (all) {
      combWritten_ = false;
      if (isect_) isect_->res_ready_i.write(m.isect.res_ready_i);
    }
  }

  std::unique_ptr<model_t> model_;
  rt_trav_unit_ports<Unit, rt_value, rt_value, value_t> last_;  // the outputs as last written
  bool combWritten_ = false;  // perf_isect_fire_o written since reset
  std::unique_ptr<rt_isect_signals> isect_;  // u_isect on signals (rt_isect_impl::rtl)
  std::unique_ptr<sc_core::sc_module> u_isect;
  sc_core::sc_event updated_;
};

}  // namespace lancer::sc
