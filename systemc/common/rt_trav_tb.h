#pragma once

#include <array>
#include <cstdint>

#include <systemc>

#include "base/rt_gated_clock.h"
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
class rt_trav_tb : public sc_core::sc_module {
 public:
  static constexpr int RESET_CYCLES = 3;
  using image_t = typename Unit::image_t;
  using slot_t = typename Unit::slot_t;
  using mem_addr_t = typename Unit::mem_addr_t;

  sc_core::sc_out<bool> clk_i{"clk_i"};
  sc_core::sc_out<bool> rst_ni{"rst_ni"};
  sc_core::sc_out<typename Unit::cfg_slots_t> cfg_slots_i{"cfg_slots_i"};
  sc_core::sc_out<typename Unit::cfg_t> cfg_i{Unit::kNames.cfgPort};

  sc_core::sc_out<bool> ray_valid_i{"ray_valid_i"};
  sc_core::sc_in<bool> ray_ready_o{"ray_ready_o"};
  sc_core::sc_out<isect_ray_t> ray_data_i{"ray_data_i"};

  sc_core::sc_in<bool> res_valid_o{"res_valid_o"};
  sc_core::sc_out<bool> res_ready_i{"res_ready_i"};
  sc_core::sc_in<typename Unit::res_t> res_data_o{"res_data_o"};

  sc_core::sc_in<bool> visit_valid_o{"visit_valid_o"};
  sc_core::sc_out<bool> visit_ready_i{"visit_ready_i"};
  sc_core::sc_in<typename Unit::visit_t> visit_data_o{"visit_data_o"};

  // Observed only (the memory model drives the responses).
  sc_core::sc_in<bool> node_req_valid_o{portName(Unit::kNames.nodePort, "req_valid_o").c_str()};
  sc_core::sc_in<mem_addr_t> node_req_addr_o{portName(Unit::kNames.nodePort, "req_addr_o").c_str()};
  sc_core::sc_in<slot_t> node_req_tag_o{portName(Unit::kNames.nodePort, "req_tag_o").c_str()};
  sc_core::sc_in<bool> node_rsp_valid_i{portName(Unit::kNames.nodePort, "rsp_valid_i").c_str()};
  sc_core::sc_in<bool> idx_req_valid_o{"idx_req_valid_o"};
  sc_core::sc_in<mem_addr_t> idx_req_addr_o{"idx_req_addr_o"};
  sc_core::sc_in<slot_t> idx_req_tag_o{"idx_req_tag_o"};
  sc_core::sc_in<bool> idx_rsp_valid_i{"idx_rsp_valid_i"};
  sc_core::sc_in<bool> tri_req_valid_o{"tri_req_valid_o"};
  sc_core::sc_in<mem_addr_t> tri_req_addr_o{"tri_req_addr_o"};
  sc_core::sc_in<slot_t> tri_req_tag_o{"tri_req_tag_o"};
  sc_core::sc_in<bool> tri_rsp_valid_i{"tri_rsp_valid_i"};
  sc_core::sc_in<bool> perf_isect_fire_o{"perf_isect_fire_o"};
  sc_core::sc_in<bool> perf_step_ready_o{"perf_step_ready_o"};

  rt_gated_clock u_clk{"u_clk"};

  SC_HAS_PROCESS(rt_trav_tb);
  explicit rt_trav_tb(sc_core::sc_module_name name)
      : sc_core::sc_module(name), stream_(Unit::kResFields, Unit::kVisitFields) {
    u_clk.clk_o(clk_i);
    SC_METHOD(stream);
    sensitive << clk_i.pos();
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
    ray_valid_i.write(false);
    res_ready_i.write(false);
    visit_ready_i.write(false);
  }

  // Edges 0 .. RESET_CYCLES-1 drive reset and the configuration; from edge
  // RESET_CYCLES on, the value written after edge e is sampled at edge e+1, which
  // ends cycle e - RESET_CYCLES.
  void stream() {
    const uint64_t edge = edge_++;
    if (edge < RESET_CYCLES) {
      rst_ni.write(false);
      cfg_i.write(cfg_);
      cfg_slots_i.write(typename Unit::cfg_slots_t(job_->slots));
      ray_valid_i.write(false);
      res_ready_i.write(false);
      visit_ready_i.write(false);
      return;
    }
    if (edge == RESET_CYCLES) {
      rst_ni.write(true);
    } else {
      const uint64_t cycle = edge - RESET_CYCLES - 1;
      if (stream_.over(visit_valid_o.read())) return finish();
      sample(cycle);
      if (!stream_.busy()) return finish();
    }
    drive(edge - RESET_CYCLES);
  }

  void sample(uint64_t cycle) {
    rt_trav_sample s;
    s.rayReady = ray_ready_o.read();
    s.resValid = res_valid_o.read();
    s.resReady = resReady_;
    s.visitValid = visit_valid_o.read();
    s.visitReady = visitReady_;
    samplePort(s, rt_trav_stream::NODE, node_req_valid_o, node_req_addr_o, node_req_tag_o, node_rsp_valid_i);
    samplePort(s, rt_trav_stream::INDEX, idx_req_valid_o, idx_req_addr_o, idx_req_tag_o, idx_rsp_valid_i);
    samplePort(s, rt_trav_stream::TRIANGLE, tri_req_valid_o, tri_req_addr_o, tri_req_tag_o, tri_rsp_valid_i);
    s.perfIsectFire = perf_isect_fire_o.read();
    s.perfStepReady = perf_step_ready_o.read();
    std::array<uint32_t, size_t(fx::wireWords(Unit::RESULT_W))> resWire{};
    std::array<uint32_t, size_t(fx::wireWords(Unit::VISIT_W))> visitWire{};
    if (s.resValid && stream_.wantsData(s.resReady)) {
      fromPort<Unit::RESULT_W>(res_data_o.read(), resWire);
      s.resWire = resWire;
    }
    if (s.visitValid && stream_.wantsData(s.visitReady)) {
      fromPort<Unit::VISIT_W>(visit_data_o.read(), visitWire);
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
    if (d.newOffer) ray_data_i.write(job_->rays[stream_.offered()]);
    ray_valid_i.write(d.rayValid);
    res_ready_i.write(d.resReady);
    visit_ready_i.write(d.visitReady);
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
