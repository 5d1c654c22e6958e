#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <systemc>

#include "base/rt_gated_clock.h"
#include "golden/records.h"
#include "isect/rt_isect_cycle.h"
#include "isect/rt_isect_ports.h"
#include "isect/rt_isect_types.h"
#include "isect/rt_pipe_kind.h"

namespace lancer::sc {

// One run of the testbench: the requests as port values, how to drive them, and
// where the results (and optionally the per-cycle port trace) go.
template <class Kind>
struct rt_pipe_job {
  std::vector<isect_ray_t> rays;
  std::vector<vl_port_t<Kind::PRIM_W>> prims;  // prims[i] (a triangle, a quadric) goes with rays[i]
  double inputIdleProbability = 0.0;    // chance per cycle the producer holds back
  double outputStallProbability = 0.0;  // chance per cycle res_ready_i is low
  uint64_t seed = 1;
  std::vector<fx::IsectResult>* results = nullptr;  // appended in delivery order
  std::vector<IsectCycle>* trace = nullptr;         // optional
  uint64_t watchdogCycles = 1'000'000;  // give up after this many cycles without a result
};

// What the testbench counted during a run, in cycles after reset.
struct rt_pipe_tally {
  uint64_t firstOffer = 0;   // cycle the first request was offered (req_valid_i high)
  uint64_t lastTake = 0;     // cycle the last result was taken (res_valid_o && res_ready_i)
  uint64_t accepted = 0;     // req_valid_i && req_ready_o
  uint64_t taken = 0;        // res_valid_o && res_ready_i
  uint64_t inputStalls = 0;  // req_valid_i && !req_ready_o
  bool busy = false;         // a run is in progress
  std::string error;         // set if the run was abandoned
};

// rt_pipe_tb<Kind>: the testbench of one implementation of a pipeline
// (rt_pipe_kind.h: rt_isect, rt_quadric). It owns the clock
// and reset and plays both stream partners; its ports carry the names of the DUT
// ports they connect to (req_valid_i is an output here), so the DUT and the
// testbench bind to the same signals with the same code.
//
//   u_clk      rt_gated_clock: a gated clock, 10 ns period; it runs only during a
//              run and comes to rest low afterwards, so sc_start() returns by
//              starvation once the run is done.
//   stream()   SC_METHOD on clk_i.posedge: first the producer, then the consumer
//              (one process, so that they draw from one random stream in a fixed
//              order). Reset for RESET_CYCLES cycles, then
//     producer offers the requests in order; when nothing is on offer it draws
//              whether to hold back this cycle (inputIdleProbability); an offered
//              request stays, unchanged, until accepted (valid never depends on
//              ready);
//     consumer takes results; res_ready_i is drawn each cycle
//              (outputStallProbability); the clock stops after the last result.
//   monitor()  SC_METHOD on clk_i.posedge: records the per-cycle trace if asked.
// The draws replicate the C++ RTL device (sw/driver/verilator_isect_device.cpp):
// one std::mt19937_64 seeded with the seed, per cycle the idle draw (if any)
// before the stall draw, a draw only for a non-zero probability, true when
// rng() < p * 2^64. So every cycle-accurate device sees the same stimulus for
// the same options, and two that behave the same report the same StreamStats.
template <class Kind>
struct rt_pipe_tb : sc_core::sc_module, Kind::template ports<sc_core::sc_out, sc_core::sc_in> {
  static constexpr int RESET_CYCLES = 2;

  sc_core::sc_out<bool> clk_i{"clk_i"};
  sc_core::sc_out<bool> rst_ni{"rst_ni"};

  rt_gated_clock u_clk{"u_clk"};

  SC_HAS_PROCESS(rt_pipe_tb);
  explicit rt_pipe_tb(sc_core::sc_module_name name);

  // Arms the testbench for one run; call while the simulation is paused, then
  // sc_start() until tally().busy is false. The job must outlive the run.
  void start(const rt_pipe_job<Kind>& job);
  const rt_pipe_tally& tally() const { return tally_; }

 private:
  void stream();
  void produce(uint64_t edge);
  void consume(uint64_t edge);
  void monitor();
  bool coin(uint64_t threshold) { return threshold != 0 && rng_() < threshold; }
  void abandon(const std::string& why);

  const rt_pipe_job<Kind>* job_ = nullptr;
  rt_pipe_tally tally_;

  uint64_t edge_ = 0;  // rising edges since start()
  std::mt19937_64 rng_;
  uint64_t idleThreshold_ = 0, stallThreshold_ = 0;
  // Producer state.
  size_t next_ = 0;  // next request to offer
  bool offered_ = false;
  // Consumer state.
  uint64_t lastProgress_ = 0;
  // Monitor state.
  uint64_t monitorEdge_ = 0;
  uint64_t monitorTaken_ = 0;
};

// Instantiated once for each pipeline, in rt_pipe_tb.cpp.
extern template struct rt_pipe_tb<isect_kind>;
extern template struct rt_pipe_tb<quadric_kind>;

}  // namespace lancer::sc
