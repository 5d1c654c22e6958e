#pragma once

#include <array>

#include <systemc>

#include "isect/rt_isect_ports.h"
#include "isect/rt_isect_types.h"

namespace lancer::sc {

// rt_isect_model: hand-written cycle model of rtl/isect/rt_isect.sv, meant to
// match it cycle for cycle and bit for bit at its ports.
//
// Latency:    ISECT_LATENCY (= fx::kIsectLatency) register stages: a request
//             accepted at an edge shows on res_valid_o ISECT_LATENCY - 1 edges
//             later, i.e. it is taken at the earliest ISECT_LATENCY cycles after
//             the cycle it was accepted in.
// Throughput: one request per cycle. Backpressure exactly as the RTL: stage s
//             loads when it is empty or stage s+1 loads (the last stage: when
//             res_ready_i), so bubbles are squeezed out during output stalls;
//             req_ready_o = stage_ready[0] depends combinationally on res_ready_i;
//             res_valid_o / res_data_o come from the last stage register.
// Reset:      rst_ni clears the valid bits asynchronously; the data registers
//             are not reset and load only with a valid item (as the RTL's).
//
// The arithmetic is not duplicated: the entry stage computes the whole result
// with fx::intersect() (the golden model) and the other stages only carry it.
// Ports (rt_isect_ports.h) carry the RTL's names and the port types Verilator generates for them
// (rt_isect_types.h), so this module and Vrt_isect_sc bind identically.
struct rt_isect_model : sc_core::sc_module, rt_isect_ports<sc_core::sc_in, sc_core::sc_out> {
  static constexpr int NUM_STAGES = ISECT_LATENCY;

  sc_core::sc_in<bool> clk_i{"clk_i"};
  sc_core::sc_in<bool> rst_ni{"rst_ni"};

  SC_HAS_PROCESS(rt_isect_model);
  explicit rt_isect_model(sc_core::sc_module_name name);

 private:
  // The stage registers: SC_METHOD on clk_i.posedge and rst_ni.negedge.
  void seq();
  // req_ready_o: SC_METHOD on res_ready_i and on every register update.
  void comb();
  // stage_ready[s] of the RTL, from the current registers and res_ready_i.
  std::array<bool, NUM_STAGES> stageReady() const;
  // The entry stage: the golden result of the request on the ports.
  isect_res_t compute() const;

  std::array<bool, NUM_STAGES> valid_q_{};
  std::array<isect_res_t, NUM_STAGES> data_q_{};
  sc_core::sc_event state_changed_;
};

}  // namespace lancer::sc
