#pragma once

#include <cstdint>

#include <systemc>

#include "common/rt_trav_stream.h"
#include "golden/octree.h"
#include "octree/rt_octree_types.h"

namespace lancer::sc {

// One run of the octree testbench: the stream (rays, options, traces) and the
// configuration (cfg_root_i = the image's node 0).
struct rt_octree_job : rt_trav_job {
  const fx::OctreeImage* image = nullptr;
};

// rt_octree_tb: the testbench of one rt_octree implementation; owns the clock
// and reset, configures the unit (cfg_slots_i, cfg_root_i), plays the ray
// producer and the result and visit consumers, and counts, through
// rt_trav_stream (the C++ Verilated devices' run loop, cycle by cycle: see
// there). Ports carry the names of the DUT ports they connect to.
//
//   clock()   SC_METHOD, a gated 10 ns clock that runs only during a run.
//   stream()  SC_METHOD on clk_i.posedge: reset for RESET_CYCLES cycles, then
//             per cycle the end test, the sample of the cycle that ends and
//             the stimulus of the next.
SC_MODULE(rt_octree_tb) {
  static constexpr int RESET_CYCLES = 3;
  static constexpr double CLOCK_PERIOD_NS = 10.0;

  sc_core::sc_out<bool> clk_i;
  sc_core::sc_out<bool> rst_ni;
  sc_core::sc_out<octree::cfg_slots_t> cfg_slots_i;
  sc_core::sc_out<octree::node_t> cfg_root_i;

  sc_core::sc_out<bool> ray_valid_i;
  sc_core::sc_in<bool> ray_ready_o;
  sc_core::sc_out<isect_ray_t> ray_data_i;

  sc_core::sc_in<bool> res_valid_o;
  sc_core::sc_out<bool> res_ready_i;
  sc_core::sc_in<octree::res_t> res_data_o;

  sc_core::sc_in<bool> visit_valid_o;
  sc_core::sc_out<bool> visit_ready_i;
  sc_core::sc_in<octree::visit_t> visit_data_o;

  // Observed only (the memory model drives the responses).
  sc_core::sc_in<bool> node_req_valid_o;
  sc_core::sc_in<octree::mem_addr_t> node_req_addr_o;
  sc_core::sc_in<octree::slot_t> node_req_tag_o;
  sc_core::sc_in<bool> node_rsp_valid_i;
  sc_core::sc_in<bool> idx_req_valid_o;
  sc_core::sc_in<octree::mem_addr_t> idx_req_addr_o;
  sc_core::sc_in<octree::slot_t> idx_req_tag_o;
  sc_core::sc_in<bool> idx_rsp_valid_i;
  sc_core::sc_in<bool> tri_req_valid_o;
  sc_core::sc_in<octree::mem_addr_t> tri_req_addr_o;
  sc_core::sc_in<octree::slot_t> tri_req_tag_o;
  sc_core::sc_in<bool> tri_rsp_valid_i;
  sc_core::sc_in<bool> perf_isect_fire_o;
  sc_core::sc_in<bool> perf_step_ready_o;

  SC_HAS_PROCESS(rt_octree_tb);
  explicit rt_octree_tb(sc_core::sc_module_name name);

  // Arms the testbench for one run; call while the simulation is paused, then
  // sc_start() until tally().busy is false. The job must outlive the run.
  void start(const rt_octree_job& job);
  const rt_trav_tally& tally() const { return stream_.tally(); }

 private:
  void clock();
  void stream();
  void sample(uint64_t cycle);
  void drive(uint64_t cycle);
  void finish();

  const rt_octree_job* job_ = nullptr;
  rt_trav_stream stream_;
  bool running_ = false;
  bool resReady_ = false, visitReady_ = false;  // what this testbench drives in the current cycle
  sc_core::sc_event start_;
  const sc_core::sc_time halfPeriod_{CLOCK_PERIOD_NS / 2, sc_core::SC_NS};
  uint64_t edge_ = 0;
};

}  // namespace lancer::sc
