#pragma once

#include <array>
#include <cstdint>

#include <systemc>

#include "base/rt_gated_clock.h"
#include "common/rt_trav_ports.h"
#include "common/rt_trav_stream.h"
#include "common/rt_trav_unit.h"
#include "isect/rt_isect_types.h"

namespace lancer::sc {

// rt_trav_tb: the testbench of one implementation of a traversal unit (Unit: a
// traits class, common/rt_trav_unit.h); owns the clock (u_clk) and reset,
// configures the unit (cfg_slots_i and the unit's configuration port,
// Unit::kNames.cfgPort), plays the ray producer and the result and visit consumers,
// and counts, through rt_trav_stream (the C++ Verilated devices' run loop,
// cycle by cycle: see there). Ports carry the names of the DUT ports they
// connect to (node_*: the unit's node/cell port, cfg_i: its kNames.cfgPort).
//
//   u_clk     a gated 10 ns clock that runs only during a run.
//   stream()  SC_METHOD on clk_i.posedge: reset for RESET_CYCLES cycles, then
//             per cycle the end test, the sample of the cycle that ends and
//             the stimulus of the next.
template <class Unit>
class rt_trav_tb : public sc_core::sc_module,
                   public rt_trav_host_ports<Unit, sc_core::sc_out, sc_core::sc_in>,
                   // observed only (the memory model drives the responses)
                   public rt_trav_node_port<Unit, sc_core::sc_in, sc_core::sc_in>,
                   public rt_trav_mem_ports<Unit, sc_core::sc_in, sc_core::sc_in> {
 public:
  static constexpr int RESET_CYCLES = 3;
  using image_t = typename Unit::image_t;
  using slot_t = typename Unit::slot_t;
  using mem_addr_t = typename Unit::mem_addr_t;
  sc_core::sc_out<typename Unit::cfg_t> cfg_i{Unit::kNames.cfgPort};

  rt_gated_clock u_clk{"u_clk"};

  SC_HAS_PROCESS(rt_trav_tb);
  explicit rt_trav_tb(sc_core::sc_module_name name)
      : sc_core::sc_module(name), stream_(Unit::kResFields, Unit::kVisitFields) {
    u_clk.clk_o(this->clk_i);
    SC_METHOD(stream);
    sensitive << this->clk_i.pos();
    dont_initialize();
  }

  // Arms the testbench for one run; call while the simulation is paused, then
  // sc_start() until tally().busy is false. The job and the image must outlive the run.
  void start(const rt_trav_job& job, const image_t& image) {
    job_ = &job;
    cfg_ = Unit::config(image);
    stream_.start(job);
    edge_ = 0;
    resReady_ = visitReady_ = false;
    u_clk.start();
  }
  const rt_trav_tally& tally() const { return stream_.tally(); }

 private:
  void finish() {
    stream_.finish();
    u_clk.stop();  // this was the last rising edge of the run
    this->ray_valid_i.write(false);
    this->res_ready_i.write(false);
    this->visit_ready_i.write(false);
  }

  // Edges 0 .. RESET_CYCLES-1 drive reset and the configuration; from edge
  // RESET_CYCLES on, the value written after edge e is sampled at edge e+1, which
  // ends cycle e - RESET_CYCLES.
  void stream() {
    const uint64_t edge = edge_++;
    if (edge < RESET_CYCLES) {
      this->rst_ni.write(false);
      cfg_i.write(cfg_);
      this->cfg_slots_i.write(typename Unit::cfg_slots_t(job_->slots));
      this->ray_valid_i.write(false);
      this->res_ready_i.write(false);
      this->visit_ready_i.write(false);
      return;
    }
    if (edge == RESET_CYCLES) {
      this->rst_ni.write(true);
    } else {
      const uint64_t cycle = edge - RESET_CYCLES - 1;
      if (stream_.over(this->visit_valid_o.read())) return finish();
      sample(cycle);
      if (!stream_.busy()) return finish();
    }
    drive(edge - RESET_CYCLES);
  }

  void sample(uint64_t cycle) {
    rt_trav_sample s;
    s.rayReady = this->ray_ready_o.read();
    s.resValid = this->res_valid_o.read();
    s.resReady = resReady_;
    s.visitValid = this->visit_valid_o.read();
    s.visitReady = visitReady_;
    samplePort(s, rt_trav_stream::NODE, this->node_req_valid_o, this->node_req_addr_o, this->node_req_tag_o, this->node_rsp_valid_i);
    samplePort(s, rt_trav_stream::INDEX, this->idx_req_valid_o, this->idx_req_addr_o, this->idx_req_tag_o, this->idx_rsp_valid_i);
    samplePort(s, rt_trav_stream::TRIANGLE, this->tri_req_valid_o, this->tri_req_addr_o, this->tri_req_tag_o, this->tri_rsp_valid_i);
    s.perfIsectFire = this->perf_isect_fire_o.read();
    s.perfStepReady = this->perf_step_ready_o.read();
    std::array<uint32_t, size_t(fx::wireWords(Unit::RESULT_W))> resWire{};
    std::array<uint32_t, size_t(fx::wireWords(Unit::VISIT_W))> visitWire{};
    if (s.resValid && stream_.wantsData(s.resReady)) {
      fromPort<Unit::RESULT_W>(this->res_data_o.read(), resWire);
      s.resWire = resWire;
    }
    if (s.visitValid && stream_.wantsData(s.visitReady)) {
      fromPort<Unit::VISIT_W>(this->visit_data_o.read(), visitWire);
      s.visitWire = visitWire;
    }
    stream_.sample(cycle, s);
  }

  static void samplePort(rt_trav_sample& s, int p, const sc_core::sc_in<bool>& reqValid,
                         const sc_core::sc_in<mem_addr_t>& reqAddr, const sc_core::sc_in<slot_t>& reqTag,
                         const sc_core::sc_in<bool>& rspValid) {
    s.req[p] = reqValid.read();
    if (s.req[p]) {
      s.addr[p] = uint32_t(reqAddr.read());
      s.tag[p] = uint32_t(reqTag.read());
    }
    s.rsp[p] = rspValid.read();
  }

  void drive(uint64_t cycle) {
    const rt_trav_stream::Drive d = stream_.drive(cycle);
    if (d.newOffer) this->ray_data_i.write(job_->rays[stream_.offered()]);
    this->ray_valid_i.write(d.rayValid);
    this->res_ready_i.write(d.resReady);
    this->visit_ready_i.write(d.visitReady);
    resReady_ = d.resReady;
    visitReady_ = d.visitReady;
  }

  const rt_trav_job* job_ = nullptr;
  typename Unit::cfg_t cfg_{};
  rt_trav_stream stream_;
  bool resReady_ = false, visitReady_ = false;  // what this testbench drives in the current cycle
  uint64_t edge_ = 0;
};

}  // namespace lancer::sc
