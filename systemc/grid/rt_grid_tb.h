#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <systemc>

#include "golden/grid.h"
#include "grid/rt_grid_cycle.h"
#include "grid/rt_grid_types.h"

namespace lancer::sc {

// One run of the grid testbench.
struct rt_grid_job {
  const fx::GridImage* image = nullptr;
  std::vector<isect_ray_t> rays;   // ray k carries ray_id = k on the port
  std::vector<uint32_t> rayIds;    // the rays' own ids, for the hits of the traces
  uint32_t slots = RAYS_IN_FLIGHT; // cfg_slots_i, 1..RAYS_IN_FLIGHT
  double inputIdleProbability = 0.0;
  double outputStallProbability = 0.0;
  uint64_t seed = 1;
  std::vector<fx::GridTrace>* traces = nullptr;  // rays.size() entries, filled in
  std::vector<GridCycle>* trace = nullptr;       // optional per-cycle port trace
  uint64_t watchdogCycles = 1'000'000;           // give up after this many cycles without progress
};

// What the testbench counted (TraversalRunStats' semantics; cycles after reset).
struct rt_grid_tally {
  uint64_t cycles = 0;  // first ray offered .. last result or visit taken, both included
  uint64_t accepted = 0, results = 0, visits = 0;
  uint64_t nodeReads = 0, indexReads = 0, triangleReads = 0;
  uint64_t isectTests = 0;
  uint64_t stepReadyCycles = 0;  // cycles with perf_step_ready_o, from the first ray offered
  std::vector<uint32_t> resultCells;  // grid_res_t.cells per ray
  bool busy = false;
  std::string error;
};

// rt_grid_tb: the testbench of one rt_grid implementation; owns the clock and
// reset, configures the unit, plays the ray producer and the result and visit
// consumers, and counts. Ports carry the names of the DUT ports they connect to.
//
//   clock()   SC_METHOD, a gated 10 ns clock that runs only during a run.
//   stream()  SC_METHOD on clk_i.posedge: reset for RESET_CYCLES cycles, then
//             per cycle, exactly as VerilatorGridDevice::run() (so that every
//             cycle-accurate grid device sees the same stimulus for the same
//             options): the loop ends before a cycle in which every result is
//             in, no memory response is outstanding and visit_valid_o is low;
//             otherwise the cycle's handshakes are counted (reads from the
//             request valids — req_ready is always 1 —, tests from
//             perf_isect_fire_o, cycles with a step ready from
//             perf_step_ready_o, visits and results taken), and the next
//             cycle's stimulus drawn from one std::mt19937_64(seed): the idle
//             draw (only with no ray on offer and rays left) before the result
//             stall draw before the visit stall draw, a draw only for a
//             non-zero probability.
SC_MODULE(rt_grid_tb) {
  static constexpr int RESET_CYCLES = 3;
  static constexpr double CLOCK_PERIOD_NS = 10.0;

  sc_core::sc_out<bool> clk_i;
  sc_core::sc_out<bool> rst_ni;
  sc_core::sc_out<cfg_res_t> cfg_res_i;
  sc_core::sc_out<cfg_slots_t> cfg_slots_i;

  sc_core::sc_out<bool> ray_valid_i;
  sc_core::sc_in<bool> ray_ready_o;
  sc_core::sc_out<isect_ray_t> ray_data_i;

  sc_core::sc_in<bool> res_valid_o;
  sc_core::sc_out<bool> res_ready_i;
  sc_core::sc_in<grid_res_t> res_data_o;

  sc_core::sc_in<bool> visit_valid_o;
  sc_core::sc_out<bool> visit_ready_i;
  sc_core::sc_in<grid_visit_t> visit_data_o;

  // Observed only (the memory model drives the responses).
  sc_core::sc_in<bool> cell_req_valid_o;
  sc_core::sc_in<mem_addr_t> cell_req_addr_o;
  sc_core::sc_in<slot_t> cell_req_tag_o;
  sc_core::sc_in<bool> cell_rsp_valid_i;
  sc_core::sc_in<bool> idx_req_valid_o;
  sc_core::sc_in<mem_addr_t> idx_req_addr_o;
  sc_core::sc_in<slot_t> idx_req_tag_o;
  sc_core::sc_in<bool> idx_rsp_valid_i;
  sc_core::sc_in<bool> tri_req_valid_o;
  sc_core::sc_in<mem_addr_t> tri_req_addr_o;
  sc_core::sc_in<slot_t> tri_req_tag_o;
  sc_core::sc_in<bool> tri_rsp_valid_i;
  sc_core::sc_in<bool> perf_isect_fire_o;
  sc_core::sc_in<bool> perf_step_ready_o;

  SC_HAS_PROCESS(rt_grid_tb);
  explicit rt_grid_tb(sc_core::sc_module_name name);

  // Arms the testbench for one run; call while the simulation is paused, then
  // sc_start() until tally().busy is false. The job must outlive the run.
  void start(const rt_grid_job& job);
  const rt_grid_tally& tally() const { return tally_; }

 private:
  void clock();
  void stream();
  void sample(uint64_t cycle);
  void drive(uint64_t cycle);
  void finish();
  void abandon(const std::string& why);
  bool coin(uint64_t threshold) { return threshold != 0 && rng_() < threshold; }

  const rt_grid_job* job_ = nullptr;
  rt_grid_tally tally_;
  bool running_ = false;
  sc_core::sc_event start_;
  uint64_t edge_ = 0;
  std::mt19937_64 rng_;
  uint64_t idleThreshold_ = 0, stallThreshold_ = 0;
  size_t offered_ = 0;
  bool offering_ = false, started_ = false;
  uint64_t firstCycle_ = 0, lastProgress_ = 0;
  uint64_t requests_[3] = {}, responses_[3] = {};  // per port: cell, index, triangle
  std::vector<uint8_t> finished_;
};

}  // namespace lancer::sc
