#pragma once

#include <cstdint>

#include <systemc>

#include "golden/grid.h"
#include "golden/stimulus.h"
#include "grid/rt_grid_types.h"

namespace lancer::sc {

// rt_grid_mem: the memory behind rt_grid's three read ports, serving one
// fx::GridImage (cell table, index list, triangle table). Behavioural model of
// a memory system, but clocked: SC_METHOD on clk_i.posedge samples the
// requests of the cycle that ends (req_ready is always 1) and drives the
// responses of the next one. Seeds seed*3+1, +2, +3 for the cell, index and
// triangle ports, as the C++ Verilated device, so that for the same
// TraversalRunOptions both see the same response times.
// Ports carry the names of the rt_grid ports they connect to.
SC_MODULE(rt_grid_mem) {
  sc_core::sc_in<bool> clk_i;

  sc_core::sc_in<bool> cell_req_valid_o;
  sc_core::sc_out<bool> cell_req_ready_i;
  sc_core::sc_in<mem_addr_t> cell_req_addr_o;
  sc_core::sc_in<slot_t> cell_req_tag_o;
  sc_core::sc_out<bool> cell_rsp_valid_i;
  sc_core::sc_out<grid_cell_t> cell_rsp_data_i;
  sc_core::sc_out<slot_t> cell_rsp_tag_i;

  sc_core::sc_in<bool> idx_req_valid_o;
  sc_core::sc_out<bool> idx_req_ready_i;
  sc_core::sc_in<mem_addr_t> idx_req_addr_o;
  sc_core::sc_in<slot_t> idx_req_tag_o;
  sc_core::sc_out<bool> idx_rsp_valid_i;
  sc_core::sc_out<idx_data_t> idx_rsp_data_i;
  sc_core::sc_out<slot_t> idx_rsp_tag_i;

  sc_core::sc_in<bool> tri_req_valid_o;
  sc_core::sc_out<bool> tri_req_ready_i;
  sc_core::sc_in<mem_addr_t> tri_req_addr_o;
  sc_core::sc_in<slot_t> tri_req_tag_o;
  sc_core::sc_out<bool> tri_rsp_valid_i;
  sc_core::sc_out<isect_tri_t> tri_rsp_data_i;
  sc_core::sc_out<slot_t> tri_rsp_tag_i;

  SC_HAS_PROCESS(rt_grid_mem);
  explicit rt_grid_mem(sc_core::sc_module_name name);

  // Arms the memory for one run (call while the simulation is paused): empties
  // the ports and reseeds them. The image must outlive the run.
  void start(const fx::GridImage& image, int latency, int jitter, uint64_t seed);
  // Stops serving (no responses, requests ignored) until the next start().
  void stop() { image_ = nullptr; }

 private:
  void edge();

  const fx::GridImage* image_ = nullptr;
  fx::MemoryReadPort cell_, idx_, tri_;  // timing: sw/golden/stimulus.h
  uint64_t cycle_ = 0;
};

}  // namespace lancer::sc
